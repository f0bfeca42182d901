#include "pipeline/report_builder.hpp"

#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include <algorithm>
#include <chrono>
#include <fstream>
#include <iostream>
#include <map>
#include <optional>
#include <sstream>

#include "closures/database_io.hpp"
#include "core/png_size.hpp"
#include "evaluation/map_metrics.hpp"
#include "evaluation/trajectory_metrics.hpp"
#include "pipeline/csv.hpp"
#include "pipeline/folder_map_store.hpp"
#include "io/cloud_files.hpp"
#include "pipeline/run_files.hpp"
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

TextTable ReadMetricsTable(const RunFolder& run) {
    TextTable table;
    std::ifstream in(run.metrics_json());
    if (!in) return table;
    const auto metrics = nlohmann::json::parse(in, nullptr, false);
    if (metrics.is_discarded() || !metrics.contains("methods")) return table;
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

}  // namespace

ReportInput LoadReportInput(const RunFolder& run) {
    const RunState state = ReadRunState(run);
    ReportInput input;
    input.title = "revisit: " + fs::path(state.dataset).filename().string();
    input.dataset_summary = {"dataset: " + state.dataset, "format: " + state.format, "poses: " + state.poses_source,
                             "scans: " + std::to_string(state.odometry.size()),
                             "length: " + FormatNumber(PathLength(state.odometry), 1) + " m",
                             state.complete ? "run complete" : "run INCOMPLETE (interrupted)"};
    if (!state.truncated.empty()) input.dataset_summary.push_back("input TRUNCATED (--allow-truncated): " + state.truncated);
    input.config_text = ReadText(run.config());
    input.counts = {{"scans", std::to_string(state.odometry.size())},
                    {"local maps", std::to_string(state.maps.size())},
                    {"closures (all methods, >= 3 inliers)", std::to_string(state.closures.size())},
                    {"closures accepted into the pose graph", std::to_string(state.NumAccepted())},
                    {"wall time [s]", FormatNumber(state.wall_seconds, 1)}};
    for (const auto& [stage, timer] : state.timings) {
        if (stage.find('.') == std::string::npos) input.timings.push_back({stage, timer.total_ms / 1000.0});
    }
    input.odometry = Timed(state, state.odometry);
    input.corrected = Timed(state, state.corrected);
    if (state.has_reference()) {
        // Ground truth lives in its own world frame: show it where the APE alignment puts it, so the
        // pictures compare what the numbers compare (SE(3) Umeyama onto the corrected trajectory).
        const Eigen::Isometry3d T_ref_est = AlignUmeyama(state.corrected, state.reference);
        Poses aligned;
        aligned.reserve(state.reference.size());
        for (const auto& T : state.reference) aligned.push_back(T_ref_est.inverse() * T);
        input.reference = Timed(state, aligned);
    }
    for (const auto& record : state.closures) {
        if (record.method != "density") continue;
        ClosureEntry entry;
        entry.closure = record.closure;
        entry.accepted = record.accepted;
        entry.reason = record.accepted ? "accepted (graph weight " + FormatNumber(record.graph_weight, 2) + ")" : record.reason;
        if (record.refined) {
            entry.fitness = record.refinement.overlap;
            entry.rmse = record.refinement.rms;
            entry.T_query_ref_refined = record.refinement.T_query_ref.matrix();
        }
        if (state.has_reference()) {
            const Eigen::Isometry3d T_est = entry.T_query_ref_refined ? Eigen::Isometry3d(*entry.T_query_ref_refined)
                                                                      : Eigen::Isometry3d(record.closure.T_query_ref);
            const ClosurePoseError error = ClosureErrorAgainst(state.reference, record.closure.query_scans.first,
                                                               record.closure.ref_scans.first, T_est);
            entry.gt_translation_error = error.translation;
            entry.gt_rotation_error = error.yaw_deg;
        }
        input.closures.push_back(entry);
    }
    input.pr_curves = ReadPrCurves(run);
    input.ape_before = ApeSeries(state, state.odometry);
    input.ape_after = ApeSeries(state, state.corrected);
    input.metrics = ReadMetricsTable(run);
    const auto maps = std::make_shared<std::vector<MapRecordSummary>>(state.maps);
    input.load_local_map = [run, maps](int id) -> std::optional<LocalMap> {
        if (id < 0 || id >= static_cast<int>(maps->size()) || !fs::exists(run.map_points(id))) return std::nullopt;
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
    for (const auto& m : state.maps) input.map_ids.push_back(m.id);
    // Keypoints live in the closure database: loaded once, on first use; without it pictures lack keypoints.
    auto keypoints = std::make_shared<std::optional<std::map<int, std::vector<Eigen::Vector2f>>>>();
    input.load_keypoints = [run, keypoints](int id) {
        if (!*keypoints) {
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
            *keypoints = std::move(by_id);
        }
        const auto it = (*keypoints)->find(id);
        return it == (*keypoints)->end() ? std::vector<Eigen::Vector2f>{} : it->second;
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

void WriteRunReport(const RunFolder& run, std::ostream& log) {
    const auto start = std::chrono::steady_clock::now();
    const auto stats = WriteReport(LoadReportInput(run), run.report_dir());
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    log << "report: " << stats.pages << " pages, " << stats.images << " pictures in " << FormatNumber(seconds, 1) << " s\n";
}

}  // namespace revisit
