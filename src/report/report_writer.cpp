#include "report/report_writer.hpp"

#include "render/map_pair_view.hpp"
#include "render/overview.hpp"
#include "report/html_page.hpp"
#include "report/map_page.hpp"
#include "report/pair_page.hpp"
#include "report/plots.hpp"
#include "report/revisit_section.hpp"
#include "report/svg_plot.hpp"

#include <cstdio>
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

/// Closure lines (accepted, and rejected after verification) join the first scans of the two maps (their map frames) on the odometry trajectory: there the
/// drift the closure corrects shows as the line's length (on the corrected trajectory both ends coincide).
OverviewData MakeOverviewData(const ReportInput& input) {
    OverviewData data;
    if (input.load_global_map) data.map_points = input.load_global_map();
    data.odometry = Positions(input.odometry);
    data.corrected = Positions(input.corrected);
    data.reference = Positions(input.reference);
    const auto& along = data.odometry.empty() ? data.corrected : data.odometry;
    for (const auto& entry : input.closures) {
        // Candidates below the inlier gate were never verified: hundreds of them would hide the map.
        if (!entry.accepted && !entry.T_query_ref_refined) continue;
        const auto q = entry.closure.query_scans.first, r = entry.closure.ref_scans.first;
        if (q < along.size() && r < along.size()) data.closures.push_back({along[q], along[r], entry.accepted});
    }
    return data;
}

std::string Navigation(std::size_t index, std::size_t count, bool link_index) {
    std::string nav = "<nav>";
    if (link_index) nav += HtmlLink("index.html", "report index");
    if (index > 0) nav += HtmlLink(ClosureStem(index - 1) + ".html", "previous closure");
    if (index + 1 < count) nav += HtmlLink(ClosureStem(index + 1) + ".html", "next closure");
    return nav + "</nav>\n";
}

std::filesystem::path ClosurePage(const ReportInput& input, std::size_t index, const std::filesystem::path& dir,
                                  const ReportConfig& config, bool link_index, std::string* thumbnail, int* images) {
    if (index >= input.closures.size())
        throw std::out_of_range("report: closure " + std::to_string(index) + " does not exist (" +
                                std::to_string(input.closures.size()) + " closures)");
    std::filesystem::create_directories(dir);
    const auto page = WritePairPage(input, input.closures[index], true, ClosureStem(index), dir, config,
                                    Navigation(index, link_index ? input.closures.size() : 0, link_index));
    if (thumbnail) *thumbnail = page.thumbnail;
    if (images) *images += page.images;
    return page.page;
}

}  // namespace

ReportConfig::ReportConfig() : pair(MapPairRenderConfig()) {}

std::filesystem::path WriteClosurePage(const ReportInput& input, std::size_t closure_index,
                                       const std::filesystem::path& report_dir, const ReportConfig& config) {
    // A page rendered alone (revisit inspect) links to the index only when there is one.
    const bool has_index = std::filesystem::exists(report_dir / "index.html");
    return ClosurePage(input, closure_index, report_dir, config, has_index, nullptr, nullptr);
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

ReportStats WriteReport(const ReportInput& input, const std::filesystem::path& report_dir, const ReportConfig& config) {
    std::filesystem::create_directories(report_dir);
    ReportStats stats;
    HtmlPage index(input.title);
    index.Raw("<nav>" + HtmlLink("#summary", "summary") + HtmlLink("#overview", "overview") +
              HtmlLink("#metrics", "metrics") + HtmlLink("#closures", "closures") + HtmlLink("#maps", "local maps") +
              HtmlLink("#config", "configuration") +
              "</nav>\n");

    index.Heading("Summary", 2, "summary");
    if (!input.dataset_summary.empty()) index.List(input.dataset_summary);
    if (!input.counts.empty()) index.KeyValueTable(input.counts);
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

    index.Heading("Overview", 2, "overview");
    const OverviewData overview = MakeOverviewData(input);
    for (const auto& [view, name, caption] : {std::tuple{OverviewView::kTopDown, "overview_top.png", "top-down"},
                                              std::tuple{OverviewView::kOblique, "overview_oblique.png", "oblique"}}) {
        WritePng(report_dir / name, RenderOverview(overview, view, config.overview));
        ++stats.images;
        index.Figure(name, std::string("overview, ") + caption, name, 640);
    }

    index.Heading("Metrics", 2, "metrics");
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

    index.Heading("Closures", 2, "closures");
    std::size_t accepted = 0;
    for (const auto& entry : input.closures) accepted += entry.accepted;
    index.Paragraph(std::to_string(input.closures.size()) + " detected, " + std::to_string(accepted) + " accepted.");
    std::string thumbs = "<div class=\"thumbs\">\n";
    for (std::size_t i = 0; i < input.closures.size(); ++i) {
        const auto& entry = input.closures[i];
        const std::string label = "#" + std::to_string(i) + ": map " + std::to_string(entry.closure.query_id) + " to " +
                                  std::to_string(entry.closure.ref_id) + ", " + std::to_string(entry.closure.num_inliers) +
                                  " inliers, " + (entry.accepted ? "accepted" : "rejected");
        if (!config.closure_pages) {
            thumbs += "<p>" + EscapeXml(label) + "</p>\n";
            continue;
        }
        std::string thumbnail;
        ClosurePage(input, i, report_dir, config, true, &thumbnail, &stats.images);
        ++stats.pages;
        thumbs += ThumbnailFigure(ClosureStem(i) + ".html", thumbnail, label, entry.accepted ? "accepted" : "rejected");
    }
    index.Raw(thumbs + "</div>\n");

    index.Heading("Local maps", 2, "maps");
    index.Paragraph(std::to_string(input.map_ids.size()) + " local maps.");
    if (config.map_pages && !input.map_ids.empty()) {
        std::string maps = "<div class=\"thumbs\">\n";
        const std::string nav = "<nav>" + HtmlLink("index.html", "report index") + "</nav>\n";
        for (const int id : input.map_ids) {
            const auto page = WriteMapPage(input, id, report_dir, config, nav);
            stats.images += page.images;
            ++stats.pages;
            maps += ThumbnailFigure(page.page.filename().string(), page.thumbnail, "map " + std::to_string(id));
        }
        index.Raw(maps + "</div>\n");
    }

    index.Heading("Configuration", 2, "config");
    index.Preformatted(input.config_text.empty() ? "(not recorded)" : input.config_text);
    WriteText(report_dir / "index.html", index.Finish());
    ++stats.pages;
    return stats;
}

}  // namespace revisit
