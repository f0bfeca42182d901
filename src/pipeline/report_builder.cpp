#include "pipeline/report_builder.hpp"

#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include <algorithm>
#include <chrono>
#include <fstream>
#include <iostream>
#include <map>
#include <mutex>
#include <optional>
#include <set>
#include <sstream>

#include "closures/database_io.hpp"
#include "core/png_size.hpp"
#include "evaluation/map_metrics.hpp"
#include "evaluation/trajectory_metrics.hpp"
#include "runfolder/csv.hpp"
#include "runfolder/folder_map_store.hpp"
#include "pipeline/interrupt.hpp"
#include "pipeline/progress.hpp"
#include "runfolder/staged_folder.hpp"
#include "pipeline/summary.hpp"
#include "io/cloud_files.hpp"
#include "runfolder/run_files.hpp"
#include "settings/scene_scale_watch.hpp"
#include "report/html_page.hpp"
#include "report/report_writer.hpp"

namespace revisit {
namespace fs = std::filesystem;

namespace {

TimedTrajectory Timed(const RunState& state, const Poses& poses) { return {state.timestamps, poses}; }

ErrorSeries ApeSeries(const RunState& state, const Poses& estimate) {
    ErrorSeries series;
    if (!state.has_reference()) return series;
    series.timestamps = state.timestamps;
    series.values = ComputeApe(estimate, state.reference, true).errors.translation;
    return series;
}

std::string ReadText(const fs::path& file) {
    std::ifstream in(file);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
}

std::vector<PrCurve> ReadPrCurves(const RunFolder& run) {
    std::vector<PrCurve> curves;
    const std::pair<const char*, const char*> methods[] = {
        {"density", "density maps"}, {"elevation", "elevation maps"}, {"scan_context", "ScanContext"}};
    for (const auto& [file_name, label] : methods) {
        const fs::path file = run.root() / (std::string("pr_curve_") + file_name + ".csv");
        if (!fs::exists(file)) continue;
        const auto table = CsvTable::Read(file);
        PrCurve curve;
        curve.method = label;
        for (std::size_t i = 0; i < table.size(); ++i) {
            curve.points.push_back({table.Number(i, "threshold"), table.Number(i, "precision"), table.Number(i, "recall")});
        }
        curves.push_back(curve);
    }
    return curves;
}

nlohmann::json ReadMetrics(const RunFolder& run) {
    std::ifstream in(run.metrics_json());
    if (!in) return {};
    auto metrics = nlohmann::json::parse(in, nullptr, false);
    return metrics.is_discarded() ? nlohmann::json{} : metrics;
}

TextTable ReadMetricsTable(const nlohmann::json& metrics) {
    TextTable table;
    if (!metrics.is_object() || !metrics.contains("methods")) return table;
    table.header = {"method", "precision", "recall", "F1", "recall @ 100% P", "APE before [m]", "APE after [m]"};
    const auto number = [](const nlohmann::json& value, int decimals) {
        return value.is_number() ? FormatNumber(value.get<double>(), decimals) : std::string("-");
    };
    for (const auto& m : metrics["methods"]) {
        table.rows.push_back({m.value("method", "?"), number(m["precision"], 3), number(m["recall"], 3), number(m["f1"], 3),
                              number(m["recall_at_100_precision"], 3), number(m["ape_rmse_before_m"], 2),
                              number(m["ape_rmse_after_m"], 2)});
    }
    return table;
}

/// Truth, coverage and missed revisits from metrics.json (nullopt for runs evaluated without them).
std::optional<RevisitFindings> ReadRevisitFindings(const nlohmann::json& metrics) {
    if (!metrics.is_object() || !metrics.contains("closure_truth") || !metrics.contains("missed_revisits")) return std::nullopt;
    RevisitFindings findings;
    const auto& truth = metrics["closure_truth"];
    const auto& coverage = metrics["revisit_coverage"];
    const auto& missed = metrics["missed_revisits"];
    findings.lines = {
        "accepted closures: " + std::to_string(truth.value("true", 0)) + " true / " + std::to_string(truth.value("false", 0)) +
            " false (true within " + FormatNumber(truth.value("true_translation_m", 0.0), 2) + " m and " +
            FormatNumber(truth.value("true_rotation_deg", 0.0), 1) + " deg of the reference)",
        "revisit coverage: " + FormatNumber(100.0 * coverage.value("coverage", 0.0), 0) + "% of " +
            std::to_string(coverage.value("revisit_scans", 0)) + " scans that come back within " +
            FormatNumber(coverage.value("radius_m", 0.0), 1) + " m of a place passed " + FormatNumber(coverage.value("gap_m", 0.0), 0) +
            " m of travel earlier lie in a map joined to it by a true closure; by the detector's closures alone (without the proximity pass): " +
            FormatNumber(100.0 * coverage.value("detector_coverage", 0.0), 0) + "%",
        "overlapping map pairs: " + std::to_string(missed.value("overlapping_map_pairs", 0)) + ", joined by a true closure: " +
            std::to_string(missed.value("found_map_pairs", 0))};
    if (missed.contains("funnel")) {
        const auto& detector = missed["funnel"]["detector"];
        const auto& proximity = missed["funnel"]["proximity"];
        findings.funnel.header = {"stage (of " + std::to_string(missed.value("overlapping_map_pairs", 0)) + " overlapping map pairs)",
                                  "detector", "proximity pass"};
        const auto row = [&](const std::string& stage, const char* key, bool both) {
            findings.funnel.rows.push_back({stage, detector[key].dump(), both ? proximity[key].dump() : "-"});
        };
        row("compared (voted for / registered)", "compared", true);
        row("enough matches", "enough_matches", false);
        row("RANSAC inliers", "ransac", false);
        row("refinement accepted", "refined", true);
        row("accepted, true", "accepted", true);
    }
    findings.per_stage.header = {"stage that lost it", "map pairs"};
    for (const auto& stage : missed["per_stage"])
        findings.per_stage.rows.push_back({stage.value("stage", "?"), stage["map_pairs"].dump()});
    findings.missed.header = {"query map", "reference map", "ground-truth scan pairs", "stage", "detail"};
    for (const auto& m : missed["missed"]) {
        findings.missed.rows.push_back({m["query_map"].dump(), m["ref_map"].dump(), m["gt_scan_pairs"].dump(),
                                        m.value("stage", ""), m.value("detail", "")});
    }
    return findings;
}

/// A partial reference's note: what the figures cover (empty when they cover the whole run).
std::string EvaluationScope(const nlohmann::json& metrics) {
    if (!metrics.is_object() || !metrics.contains("reference")) return "";
    const auto& r = metrics["reference"];
    const auto count = [&r](const char* key) { return std::to_string(r.value(key, std::size_t{0})); };
    std::string scope = "The reference poses cover " + count("paired_scans") + " of " + count("scans") +
                        " scans: APE, RPE and the KITTI errors are those scans'. ";
    if (!metrics.contains("methods"))
        return scope + "No local map lies wholly within the reference, so there are no closure metrics.";
    return scope + "The closure figures (ground truth, precision and recall, closure truth, revisit coverage, missed revisits) cover " +
           count("evaluated_scans") + " of " + count("scans") + " scans: the " + count("evaluated_maps") + " of " + count("maps") +
           " local maps the reference covers whole. " + count("left_out_closures") + " closure candidates (" +
           count("left_out_accepted_closures") + " accepted) involve scans without a reference pose and are left out.";
}

/// Accepted closures the evaluation judged false, by (query first scan, reference first scan).
std::set<std::pair<std::size_t, std::size_t>> FalseClosures(const nlohmann::json& metrics) {
    std::set<std::pair<std::size_t, std::size_t>> result;
    if (!metrics.is_object() || !metrics.contains("closure_truth")) return result;
    for (const auto& c : metrics["closure_truth"]["accepted"]) {
        if (!c.value("true", true)) result.emplace(c.value("query_first_scan", std::size_t{0}), c.value("ref_first_scan", std::size_t{0}));
    }
    return result;
}

}  // namespace

ReportInput LoadReportInput(const RunFolder& run) {
    RunState state = ReadRunState(run);  // its closures move into the input: one copy of their matches
    ReportInput input;
    input.title = "revisit: " + fs::path(state.dataset).filename().string();
    input.dataset_summary = {"dataset: " + state.dataset, "format: " + state.format, "poses: " + state.poses_source,
                             "scans: " + std::to_string(state.odometry.size()),
                             "length: " + FormatNumber(PathLength(state.odometry), 1) + " m",
                             state.complete ? "run complete" : "run INCOMPLETE (interrupted)"};
    if (!state.truncated.empty()) input.dataset_summary.push_back("input TRUNCATED (--allow-truncated): " + state.truncated);
    input.config_text = ReadText(run.config());
    // Closure counts are the index's "at a glance" table (from input.closures); these are the run's.
    input.counts = {{"scans", std::to_string(state.odometry.size())},
                    {"local maps", std::to_string(state.maps.size())},
                    {"chain wall time (before evaluation and report) [s]", FormatNumber(state.wall_seconds, 1)}};
    input.run_dir = run.root().string();
    for (const auto& [stage, timer] : state.timings) {
        if (stage.find('.') == std::string::npos) input.timings.push_back({stage, timer.total_ms / 1000.0});
    }
    input.odometry = Timed(state, state.odometry);
    input.odometry_fallbacks = state.odometry_fallbacks;
    for (const auto& update : state.setting_updates) input.setting_updates.push_back(DescribeUpdate(update));
    input.corrected = Timed(state, state.corrected);
    input.reference_is_input = ReferenceIsInput(state);
    if (state.has_reference()) {
        // Ground truth lives in its own world frame: show it where the APE alignment puts it, so the
        // pictures compare what the numbers compare (SE(3) Umeyama onto the corrected trajectory).
        const Eigen::Isometry3d T_ref_est = AlignUmeyama(state.corrected, state.reference);
        Poses aligned;
        aligned.reserve(state.reference.size());
        for (const auto& T : state.reference) aligned.push_back(T_ref_est.inverse() * T);
        input.reference = Timed(state, aligned);
    }
    const nlohmann::json metrics = ReadMetrics(run);
    const auto false_closures = FalseClosures(metrics);
    for (auto& record : state.closures) {
        // The proximity pass's registrations (no images matched: 0 votes, 0 inliers) are shown when accepted.
        const bool proximity = record.method == "proximity";
        input.proximity_registered += proximity;
        if (record.method != "density" && !(proximity && record.accepted)) continue;
        ClosureEntry entry;
        entry.closure = std::move(record.closure);
        entry.proximity = proximity;
        entry.accepted = record.accepted;
        entry.reached_threshold = record.refined;
        entry.verified = record.refined && record.refinement.accepted;
        entry.reason = record.accepted ? "graph weight " + FormatNumber(record.graph_weight, 2) : record.reason;
        if (record.accepted && false_closures.count({entry.closure.query_scans.first, entry.closure.ref_scans.first})) {
            entry.reason += ", FALSE against the reference poses";
            entry.judged_false = true;
        }
        if (record.refined) {
            entry.fitness = record.refinement.overlap;
            entry.rmse = record.refinement.rms;
            entry.T_query_ref_refined = record.refinement.T_query_ref.matrix();
        }
        if (state.has_reference()) {
            const Eigen::Isometry3d T_est = entry.T_query_ref_refined ? Eigen::Isometry3d(*entry.T_query_ref_refined)
                                                                      : Eigen::Isometry3d(entry.closure.T_query_ref);
            const ClosurePoseError error = ClosureErrorAgainst(state.reference, entry.closure.query_scans.first,
                                                               entry.closure.ref_scans.first, T_est);
            entry.gt_translation_error = error.translation;
            entry.gt_rotation_error = error.yaw_deg;
        }
        input.closures.push_back(std::move(entry));
    }
    input.pr_curves = ReadPrCurves(run);
    input.ape_before = ApeSeries(state, state.odometry);
    input.ape_after = ApeSeries(state, state.corrected);
    input.metrics = ReadMetricsTable(metrics);
    input.revisits = ReadRevisitFindings(metrics);
    input.evaluation_scope = EvaluationScope(metrics);
    if (metrics.is_object() && metrics.contains("closure_truth")) {
        input.true_closures = metrics["closure_truth"].value("true", 0);
        input.false_closures = metrics["closure_truth"].value("false", 0);
    }
    const auto maps = std::make_shared<std::vector<MapRecordSummary>>(state.maps);
    input.load_local_map = [run, maps](int id) -> std::optional<LocalMap> {
        if (id < 0 || id >= static_cast<int>(maps->size()) || !HasMapPoints(run, id)) return std::nullopt;
        const auto& m = (*maps)[id];
        LocalMap map;
        map.id = id;
        map.first_scan = m.first_scan;
        map.last_scan = m.last_scan;
        map.T_world_map = m.T_world_map;
        map.points = ReadMapPoints(run, id);
        return map;
    };
    const int max_image_side = LoadConfig({run.config().string()}, {}).detector.density.max_image_side;
    input.load_density_image = [run, maps, max_image_side](int id) -> std::optional<DensityImage> {
        if (id < 0 || id >= static_cast<int>(maps->size()) || !fs::exists(run.map_density(id))) return std::nullopt;
        // Bounded before decoding: a damaged header must not make the decoder allocate gigabytes.
        CheckPngSize(ReadPngSize(run.map_density(id)), max_image_side, run.map_density(id));
        DensityImage image;
        image.image = cv::imread(run.map_density(id).string(), cv::IMREAD_GRAYSCALE);
        image.origin = (*maps)[id].density_origin;
        image.resolution = (*maps)[id].density_resolution;
        if (image.image.empty()) return std::nullopt;
        return image;
    };
    for (const auto& m : state.maps) {
        input.map_ids.push_back(m.id);
        input.map_scans.push_back({m.first_scan, m.last_scan});
    }
    // Keypoints live in the closure database: loaded once, on first use (pages render in parallel: call_once);
    // without it pictures lack keypoints.
    struct KeypointCache {
        std::once_flag loaded;
        std::map<int, std::vector<Eigen::Vector2f>> by_id;
    };
    auto keypoints = std::make_shared<KeypointCache>();
    input.load_keypoints = [run, keypoints](int id) {
        std::call_once(keypoints->loaded, [&] {
            std::map<int, std::vector<Eigen::Vector2f>> by_id;
            try {
                const auto detector = LoadDatabase(run.database(), LoadConfig({run.config().string()}, {}).detector);
                // The run's own maps are the last session stored (LoadDatabase opens a new one after them).
                int last_session = 0;
                for (const auto& record : detector.maps()) last_session = std::max(last_session, record.session);
                for (const auto& record : detector.maps())
                    if (record.session == last_session) by_id[record.id] = record.keypoints;
            } catch (const std::exception& e) {
                // No database, or one this build cannot read: the pages are still useful without keypoints,
                // but the user is told which file and why (`revisit inspect` fails instead: CheckRunDatabase).
                std::cerr << "warning: " << e.what() << "; the report's pictures show no keypoints\n";
            }
            keypoints->by_id = std::move(by_id);
        });
        const auto it = keypoints->by_id.find(id);
        return it == keypoints->by_id.end() ? std::vector<Eigen::Vector2f>{} : it->second;
    };
    input.load_global_map = [run]() {
        std::vector<Eigen::Vector3f> points;
        if (!fs::exists(run.corrected_map())) return points;
        return LoadPly(run.corrected_map()).points;
    };
    return input;
}

void CheckRunDatabase(const RunFolder& run) {
    LoadDatabase(run.database(), LoadConfig({run.config().string()}, {}).detector);
}

ReportConfig RunReportConfig(const RunFolder& run, const std::vector<std::string>& overrides) {
    const PipelineConfig config =
        LoadConfig(fs::exists(run.config()) ? std::vector<std::string>{run.config().string()} : std::vector<std::string>{},
                   overrides);
    ReportConfig report;
    report.pages.strongest_candidates = config.output.report_candidates;
    report.pages.closure_budget = config.output.report_closure_pages;
    report.pages.map_budget = config.output.report_map_pages;
    return report;
}

double WriteRunReport(const RunFolder& run, std::ostream& log, const ReportRunOptions& options) {
    const auto start = std::chrono::steady_clock::now();
    const ReportConfig report_config = RunReportConfig(run, options.overrides);
    // The new report is built beside the old one and swapped in when complete: a failing input or
    // Ctrl-C leaves the old report as it was. Only the kinds of file the report writes are ever
    // removed, never through a link (runfolder/staged_folder.hpp).
    StagedFolder staged(run.report_dir(), {".html", ".png", ".svg"});
    const auto stop_if_interrupted = [] {
        if (InterruptRequested()) throw Interrupted("interrupted; the report was not replaced");
    };
    stop_if_interrupted();
    const ReportInput input = LoadReportInput(run);
    // The database is read once, up front: a damaged one is reported even when no rendered page needs keypoints.
    if (!input.map_ids.empty() && input.load_keypoints) input.load_keypoints(input.map_ids.front());
    CountedProgress progress(log, Progress::DetectMode(options.quiet), "pages");
    const auto stats = WriteReport(input, staged.path(), report_config, [&](std::size_t done, std::size_t total) {
        stop_if_interrupted();
        progress(done, total);
    });
    stop_if_interrupted();
    const fs::path kept = staged.Commit();
    if (!kept.empty()) {
        log << "warning: the previous " << run.report_dir().string() << " held files revisit did not write; kept them in "
            << kept.string() << '\n';
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    log << "report: " << stats.pages << " pages, " << stats.images << " pictures in " << FormatNumber(seconds, 1) << " s\n";
    return seconds;
}

}  // namespace revisit
