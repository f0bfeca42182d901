#include "report/report_writer.hpp"

#include "render/map_pair_view.hpp"
#include "render/map_top_view.hpp"
#include "render/overview.hpp"
#include "report/html_page.hpp"
#include "report/index_tables.hpp"
#include "report/map_page.hpp"
#include "report/pair_page.hpp"
#include "report/plots.hpp"
#include "report/revisit_section.hpp"
#include "report/svg_plot.hpp"

#include <oneapi/tbb/blocked_range.h>
#include <oneapi/tbb/parallel_for.h>

#include <algorithm>
#include <cstdio>
#include <mutex>
#include <stdexcept>
#include <tuple>

namespace revisit {
namespace {

/// An index thumbnail linking to its page; the label alone when there is no picture.
std::string ThumbnailFigure(const std::string& page, const std::string& thumbnail, const std::string& label,
                            const std::string& css_class = "") {
    const std::string image = "<img" + (css_class.empty() ? std::string() : " class=\"" + css_class + "\"") + " src=\"" +
                              EscapeXml(thumbnail) + "\" alt=\"" + EscapeXml(label) + "\">";
    return "<figure><a href=\"" + EscapeXml(page) + "\">" + (thumbnail.empty() ? EscapeXml(label) : image) +
           "</a><figcaption>" + EscapeXml(label) + "</figcaption></figure>\n";
}

std::vector<Eigen::Vector3d> Positions(const TimedTrajectory& trajectory) {
    std::vector<Eigen::Vector3d> positions;
    positions.reserve(trajectory.T_world_sensor.size());
    for (const auto& T : trajectory.T_world_sensor) positions.push_back(T.translation());
    return positions;
}

/// Closures are drawn where the run came back: the middle scan of the query (revisiting) map on the corrected
/// trajectory, where the two maps coincide once corrected. Candidates below the inlier gate are left out.
OverviewData MakeOverviewData(const ReportInput& input) {
    OverviewData data;
    if (input.load_global_map) data.map_points = input.load_global_map();
    data.odometry = Positions(input.odometry);
    data.corrected = Positions(input.corrected);
    data.reference = Positions(input.reference);
    const auto& along = data.corrected.empty() ? data.odometry : data.corrected;
    for (const auto& entry : input.closures) {
        // Candidates below the inlier gate were never verified: hundreds of them would hide the map.
        if (!entry.accepted && !entry.T_query_ref_refined) continue;
        const auto q = (entry.closure.query_scans.first + entry.closure.query_scans.last) / 2;
        if (q < along.size()) data.closures.push_back({along[q], entry.accepted});
    }
    return data;
}

/// Links to the index and to the previous and next closure that have a page.
std::string Navigation(const ReportPlan& plan, std::size_t index, bool link_index) {
    std::string nav = "<nav>";
    if (link_index) nav += HtmlLink("index.html", "report index");
    const auto& pages = plan.closure_pages;
    const auto it = std::lower_bound(pages.begin(), pages.end(), index);
    if (it != pages.begin()) nav += HtmlLink(ClosureStem(*(it - 1)) + ".html", "previous closure page");
    const auto next = it != pages.end() && *it == index ? it + 1 : it;
    if (next != pages.end()) nav += HtmlLink(ClosureStem(*next) + ".html", "next closure page");
    return nav + "</nav>\n";
}

void CheckClosureIndex(const ReportInput& input, std::size_t index) {
    if (index >= input.closures.size())
        throw std::out_of_range("report: closure " + std::to_string(index) + " does not exist (" +
                                std::to_string(input.closures.size()) + " closures)");
}

/// The plan of the report in `report_dir`, for a page rendered alone: links only where the index put pages.
ReportPlan PlanForSinglePage(const ReportInput& input, const std::filesystem::path& report_dir, const ReportConfig& config,
                             bool* has_index) {
    *has_index = std::filesystem::exists(report_dir / "index.html");
    return *has_index ? PlanReport(input, config.pages)
                      : PlanReport(input, ReportPagePlan{0, 0, false, false, 0});
}

/// One page to render: a closure's (index into input.closures) or a map's (id).
struct PageTask {
    bool is_closure = true;
    std::size_t closure = 0;
    int map_id = 0;
};

}  // namespace

ReportConfig::ReportConfig() : pair(MapPairRenderConfig()) {
    // Rendered at the size the index shows them: a larger frame would only be scaled down by the browser.
    overview.width = 1000;
    overview.height = 750;
}

std::filesystem::path WriteClosurePage(const ReportInput& input, std::size_t closure_index,
                                       const std::filesystem::path& report_dir, const ReportConfig& config) {
    CheckClosureIndex(input, closure_index);
    bool has_index = false;
    const ReportPlan plan = PlanForSinglePage(input, report_dir, config, &has_index);
    std::filesystem::create_directories(report_dir);
    return WritePairPage(input, input.closures[closure_index], true, ClosureStem(closure_index), report_dir, config,
                         Navigation(plan, closure_index, has_index))
        .page;
}

std::filesystem::path WriteSingleMapPage(const ReportInput& input, int map_id, const std::filesystem::path& report_dir,
                                         const ReportConfig& config) {
    if (std::find(input.map_ids.begin(), input.map_ids.end(), map_id) == input.map_ids.end())
        throw std::out_of_range("report: local map " + std::to_string(map_id) + " does not exist (" +
                                std::to_string(input.map_ids.size()) + " maps)");
    bool has_index = false;
    const ReportPlan plan = PlanForSinglePage(input, report_dir, config, &has_index);
    std::filesystem::create_directories(report_dir);
    const std::string nav = has_index ? "<nav>" + HtmlLink("index.html", "report index") + "</nav>\n" : std::string();
    return WriteMapPage(input, map_id, report_dir, config, plan, nav).page;
}

std::filesystem::path WriteMapPairPage(const ReportInput& input, int query_map_id, int ref_map_id,
                                       const std::filesystem::path& report_dir, const ReportConfig& config) {
    ClosureEntry entry;
    entry.closure.query_id = query_map_id;
    entry.closure.ref_id = ref_map_id;
    if (input.load_local_map) {
        // Scan ranges from the maps themselves (the odometry pose of the pair is read from them too).
        if (auto map = input.load_local_map(query_map_id)) entry.closure.query_scans = {map->first_scan, map->last_scan};
        if (auto map = input.load_local_map(ref_map_id)) entry.closure.ref_scans = {map->first_scan, map->last_scan};
    }
    if (input.load_keypoints) {
        entry.closure.query_keypoints = input.load_keypoints(query_map_id);
        entry.closure.ref_keypoints = input.load_keypoints(ref_map_id);
    }
    std::filesystem::create_directories(report_dir);
    const std::string stem = "maps_" + std::to_string(query_map_id) + "_" + std::to_string(ref_map_id);
    const std::string nav = std::filesystem::exists(report_dir / "index.html")
                                ? "<nav>" + HtmlLink("index.html", "report index") + "</nav>\n"
                                : std::string();
    return WritePairPage(input, entry, false, stem, report_dir, config, nav).page;
}

ReportStats WriteReport(const ReportInput& input, const std::filesystem::path& report_dir, const ReportConfig& config,
                        const ReportProgress& progress) {
    std::filesystem::create_directories(report_dir);
    const ReportPlan plan = PlanReport(input, config.pages);

    // Pages first, in parallel: each writes only its own files; thumbnails and counts land in their slots.
    std::vector<PageTask> tasks;
    for (const std::size_t i : plan.closure_pages) tasks.push_back({true, i, 0});
    for (const int id : plan.map_pages) tasks.push_back({false, 0, id});
    std::vector<WrittenPage> written(tasks.size());
    const std::size_t total_pages = tasks.size() + 1;
    std::mutex progress_mutex;
    std::size_t pages_done = 0;
    if (progress) progress(0, total_pages);
    const std::string index_nav = "<nav>" + HtmlLink("index.html", "report index") + "</nav>\n";
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, tasks.size(), 1), [&](const tbb::blocked_range<std::size_t>& range) {
        for (std::size_t t = range.begin(); t != range.end(); ++t) {
            const PageTask& task = tasks[t];
            written[t] = task.is_closure ? WritePairPage(input, input.closures[task.closure], true, ClosureStem(task.closure),
                                                         report_dir, config, Navigation(plan, task.closure, true))
                                         : WriteMapPage(input, task.map_id, report_dir, config, plan, index_nav);
            std::lock_guard<std::mutex> lock(progress_mutex);
            ++pages_done;
            if (progress) progress(pages_done, total_pages);
        }
    });
    ReportStats stats;
    for (const auto& page : written) stats.images += page.images, ++stats.pages;

    HtmlPage index(input.title);
    index.Raw("<nav>" + HtmlLink("#summary", "summary") + HtmlLink("#overview", "overview") +
              HtmlLink("#metrics", "metrics") + HtmlLink("#closures", "closures") +
              HtmlLink("#candidates", "all candidates") + HtmlLink("#maps", "local maps") +
              HtmlLink("#timing", "timing") + HtmlLink("#config", "configuration") + "</nav>\n");

    index.Heading("Summary", 2, "summary");
    if (!input.dataset_summary.empty()) index.List(input.dataset_summary);
    index.Raw("<div class=\"glance\">\n");
    index.KeyValueTable(GlanceCounts(input, plan));
    index.Raw("</div>\n");
    if (!input.counts.empty()) index.KeyValueTable(input.counts);

    index.Heading("Overview", 2, "overview");
    const OverviewData overview = MakeOverviewData(input);
    for (const auto& [view, name, caption] : {std::tuple{OverviewView::kTopDown, "overview_top.png", "top-down"},
                                              std::tuple{OverviewView::kOblique, "overview_oblique.png", "oblique"}}) {
        WritePng(report_dir / name, RenderOverview(overview, view, config.overview));
        ++stats.images;
        index.Figure(name, std::string("overview, ") + caption, name);
    }
    // The corrected map alone, one pixel per cell: single or doubled walls show here.
    WritePng(report_dir / "map_top.png", RenderMapTopView(overview.map_points));
    ++stats.images;
    index.Figure("map_top.png", "corrected map, top view (every point of the global map at the corrected poses)", "map_top.png");

    index.Heading("Accepted closures by ground-truth error", 2, "errors");
    AddErrorRanking(index, input, plan, 5);

    index.Heading("Metrics", 2, "metrics");
    if (!input.evaluation_scope.empty()) index.Paragraph(input.evaluation_scope);
    if (input.reference_is_input)
        index.Paragraph("reference = input poses: the run used the dataset's own poses (--poses dataset), which are also "
                        "its reference. APE before is zero by construction; APE after is how far the closures moved "
                        "the trajectory from the input, not an error against an independent reference.");
    if (!input.metrics.rows.empty()) index.Table(input.metrics.header, input.metrics.rows);
    if (!input.pr_curves.empty()) {
        WriteText(report_dir / "precision_recall.svg", PrCurvesSvg(input.pr_curves));
        ++stats.images;
        index.Figure("precision_recall.svg", "precision-recall of every evaluated method");
    }
    if (!input.ape_before.values.empty() || !input.ape_after.values.empty()) {
        WriteText(report_dir / "ape_over_time.svg", ApeOverTimeSvg(input.ape_before, input.ape_after));
        ++stats.images;
        index.Figure("ape_over_time.svg", "APE over time, before and after correction");
    }
    if (!input.ape_after.values.empty() && !input.corrected.Empty()) {
        WriteText(report_dir / "trajectory_ape.svg", TrajectoryApeSvg(input.corrected, input.ape_after));
        ++stats.images;
        index.Figure("trajectory_ape.svg", "corrected trajectory coloured by APE");
    }
    if (input.metrics.rows.empty() && input.pr_curves.empty() && input.ape_after.values.empty())
        index.Paragraph("No evaluation in this run (no ground truth).");

    AddRevisitSection(index, input);

    index.Heading("Closure pages", 2, "closures");
    index.Paragraph(std::to_string(plan.closure_pages.size()) + " of " + std::to_string(input.closures.size()) +
                    " candidates have a page: of those that reached the acceptance threshold, every one when they are " +
                    std::to_string(config.pages.closure_budget) +
                    " or fewer, else every false one, the worst, the best and an even sample; and the " +
                    std::to_string(config.pages.strongest_candidates) +
                    " strongest below it. Any other: `" + std::string(kInspectCommand) + " --closure N`" +
                    (input.run_dir.empty() ? std::string(".") : " (RUN_DIR: " + input.run_dir + ")."));
    std::string thumbs = "<div class=\"thumbs\">\n";
    for (std::size_t t = 0; t < tasks.size(); ++t) {
        if (!tasks[t].is_closure) continue;
        const std::size_t i = tasks[t].closure;
        const auto& entry = input.closures[i];
        const std::string label = "#" + std::to_string(i) + ": map " + std::to_string(entry.closure.query_id) + " to " +
                                  std::to_string(entry.closure.ref_id) + ", " + ClosureEvidence(entry) + ", " +
                                  ClosureStatus(entry);
        thumbs += ThumbnailFigure(ClosureStem(i) + ".html", written[t].thumbnail, label, entry.accepted ? "accepted" : "rejected");
    }
    index.Raw(thumbs + "</div>\n");

    index.Heading("All closure candidates", 2, "candidates");
    index.Paragraph("One row per candidate; click a header to sort, type to filter (with scripts on).");
    AddCandidateTable(index, input, plan);

    index.Heading("Local maps", 2, "maps");
    index.Paragraph(std::to_string(input.map_ids.size()) + " local maps; " + std::to_string(plan.map_pages.size()) +
                    " pages (the maps of the closure pages). Any other: `" + std::string(kInspectCommand) + " --map N`.");
    std::string maps = "<div class=\"thumbs\">\n";
    for (std::size_t t = 0; t < tasks.size(); ++t) {
        if (tasks[t].is_closure) continue;
        maps += ThumbnailFigure(written[t].page.filename().string(), written[t].thumbnail, "map " + std::to_string(tasks[t].map_id));
    }
    index.Raw(maps + "</div>\n");
    AddMapTable(index, input, plan);

    if (!input.odometry_fallbacks.empty()) {
        index.Heading("Odometry fallbacks", 2, "odometry");
        WriteText(report_dir / "odometry_fallbacks.svg", OdometryFallbacksSvg(input.odometry, input.odometry_fallbacks));
        ++stats.images;
        index.Paragraph("The odometry fell back to the motion prediction on " + std::to_string(input.odometry_fallbacks.size()) +
                        " scans (degenerate or diverged registration; run.json lists them). They are red here:");
        index.Figure("odometry_fallbacks.svg", "odometry trajectory, motion predictions in red");
    }

    if (!input.setting_updates.empty()) {
        index.Heading("Settings that followed the data", 2, "settings");
        index.Paragraph("Settings the data changed as the sequence unfolded: the odometry's range when the scene's scale changed, the heading-drift rate the closures measured, the global map's voxel when the map would have passed its cap (run.json: setting_updates):");
        for (const auto& line : input.setting_updates) index.Paragraph(line);
    }

    index.Heading("Time per stage", 2, "timing");
    if (input.timings.empty()) index.Paragraph("Not recorded.");
    if (!input.timings.empty()) {
        std::vector<std::pair<std::string, std::string>> rows;
        double total = 0.0;
        for (const auto& t : input.timings) rows.emplace_back(t.stage, FormatNumber(t.seconds, 2) + " s"), total += t.seconds;
        rows.emplace_back("total", FormatNumber(total, 2) + " s");
        index.KeyValueTable(rows);
        WriteText(report_dir / "timing.svg", TimingSvg(input.timings));
        ++stats.images;
        index.Figure("timing.svg", "time per stage");
    }

    index.Heading("Configuration", 2, "config");
    index.Preformatted(input.config_text.empty() ? "(not recorded)" : input.config_text);
    WriteText(report_dir / "index.html", index.Finish());
    ++stats.pages;
    if (progress) progress(total_pages, total_pages);
    return stats;
}

}  // namespace revisit
