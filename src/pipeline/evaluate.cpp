#include "pipeline/evaluate.hpp"

#include "runfolder/json_file.hpp"
#include "core/atomic_file.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <fstream>
#include <iomanip>

#include "evaluation/ground_truth_closures.hpp"
#include "pipeline/dataset_pass.hpp"
#include "evaluation/scan_context.hpp"
#include "pipeline/covered_run.hpp"
#include "pipeline/progress.hpp"

namespace revisit {
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

/// ScanContext searches every scan of the run, as with a full reference; the candidates between two
/// evaluated scans are kept, at their evaluated positions.
std::vector<ScanContextCandidate> EvaluatedCandidates(std::vector<ScanContextCandidate> candidates,
                                                      const std::vector<std::size_t>& scans) {
    if (scans.empty()) return candidates;
    std::vector<ScanContextCandidate> kept;
    const auto position = [&scans](std::size_t scan) -> std::optional<std::size_t> {
        const auto it = std::lower_bound(scans.begin(), scans.end(), scan);
        if (it == scans.end() || *it != scan) return std::nullopt;
        return static_cast<std::size_t>(it - scans.begin());
    };
    for (auto c : candidates) {
        const auto query = position(c.query), candidate = position(c.candidate);
        if (!query || !candidate) continue;
        c.query = *query;
        c.candidate = *candidate;
        kept.push_back(c);
    }
    return kept;
}

/// tau_d as given, or (0) the distance within which the ground truth's revisit segment pairs mostly
/// overlap: a map closure then predicts the scan pairs its two maps share by the ground truth's own rule
/// of thumb for this sensor here, not at the paper's 6 m, which is a 64-beam car's in KITTI's streets.
PredictedClosureConfig PredictionAtTheDataScale(PredictedClosureConfig predicted, const GtClosures& gt, RunEvaluation& e) {
    constexpr double kPaperTauD = 6.0;  // [m] thesis section 5.1
    e.tau_d_source = "given";
    if (predicted.max_distance <= 0.0) {
        const double from_overlap = OverlapDistance(gt);
        predicted.max_distance = from_overlap > 0.0 ? from_overlap : kPaperTauD;
        e.tau_d_source = from_overlap > 0.0 ? "overlap" : "paper";
    }
    e.tau_d = predicted.max_distance;
    return predicted;
}

std::optional<GtClosures> ReadCache(const fs::path& file, const std::string& key) {
    std::ifstream in(file);
    return in ? ReadGroundTruthClosures(in, key) : std::nullopt;
}

MapClosureForEval ForEval(const ClosureRecord& record) {
    const auto& c = record.closure;
    MapClosureForEval e;
    e.query_first_scan = c.query_scans.first;
    e.query_last_scan = c.query_scans.last;
    e.ref_first_scan = c.ref_scans.first;
    e.ref_last_scan = c.ref_scans.last;
    // The refined pose where there is one: it is what the graph uses.
    e.T_query_ref = record.refined && record.accepted ? record.refinement.T_query_ref : Eigen::Isometry3d(c.T_query_ref);
    e.inliers = c.num_inliers;
    return e;
}

std::vector<MapClosureForEval> ForEval(const RunState& state, const std::string& method) {
    std::vector<MapClosureForEval> out;
    for (const auto& record : state.closures)
        if (record.method == method) out.push_back(ForEval(record));
    return out;
}

/// The accepted closures that correct the trajectory (the detector's and the proximity pass's), for
/// their truth, in run order; `methods` gets each one's method.
std::vector<MapClosureForEval> Accepted(const RunState& state, std::vector<std::string>& methods) {
    std::vector<MapClosureForEval> accepted;
    for (const auto& record : state.closures) {
        if (!record.accepted || !CorrectsTrajectory(record)) continue;
        accepted.push_back(ForEval(record));
        methods.push_back(record.method);
    }
    return accepted;
}

TrajectoryEvaluation EvaluateTrajectory(const Poses& estimate, const Poses& reference) {
    return {ComputeApe(estimate, reference, true), ComputeRpe(estimate, reference, 1), ComputeKittiErrors(estimate, reference)};
}

json StatsJson(const ErrorStatistics& s) {
    return {{"rmse", s.rmse}, {"mean", s.mean}, {"median", s.median}, {"std", s.std}, {"min", s.min}, {"max", s.max}, {"count", s.count}};
}

json TrajectoryJson(const TrajectoryEvaluation& t) {
    return {{"ape_translation_m", StatsJson(t.ape.errors.translation_stats)},
            {"ape_rotation_deg", StatsJson(t.ape.errors.rotation_deg_stats)},
            {"rpe_translation_m", StatsJson(t.rpe.translation_stats)},
            {"rpe_rotation_deg", StatsJson(t.rpe.rotation_deg_stats)},
            {"kitti_translation_percent", t.kitti.translation_percent},
            {"kitti_rotation_deg_per_100m", t.kitti.rotation_deg_per_100m},
            {"kitti_segments", t.kitti.num_segments}};
}

/// The proximity pass has no votes or RANSAC: those stages are left out of its column.
json FunnelJson(const RecallFunnel& f, bool detector) {
    json j = {{"compared", f.compared}, {"refined", f.refined}, {"accepted", f.accepted}};
    if (detector) j["enough_matches"] = f.enough_matches, j["ransac"] = f.ransac;
    return j;
}

/// `scans`: the run's scan at each evaluated position (empty: the same).
json VerificationJson(const RunEvaluation& e, const std::vector<MapClosureForEval>& accepted, const std::vector<std::string>& methods,
                      const std::vector<std::size_t>& scans, const ClosureTruthConfig& config) {
    json closures = json::array();
    for (std::size_t k = 0; k < accepted.size(); ++k) {
        const auto& verdict = e.truth.verdicts[k];
        closures.push_back({{"method", methods[k]}, {"query_first_scan", RunScan(scans, accepted[k].query_first_scan)},
                            {"ref_first_scan", RunScan(scans, accepted[k].ref_first_scan)},
                            {"query_anchor_scan", RunScan(scans, verdict.query_scan)},
                            {"ref_anchor_scan", RunScan(scans, verdict.ref_scan)},
                            {"true", verdict.is_true}, {"translation_error_m", verdict.error.translation},
                            {"yaw_error_deg", verdict.error.yaw_deg},
                            {"first_scan_translation_error_m", verdict.first_scan_error.translation},
                            {"first_scan_yaw_error_deg", verdict.first_scan_error.yaw_deg}});
    }
    json per_stage = json::array();  // in chain order
    for (const auto& [stage, count] : e.missed.per_stage) per_stage.push_back({{"stage", MissStageName(stage)}, {"map_pairs", count}});
    json missed = json::array();
    for (const auto& m : e.missed.missed) {
        missed.push_back({{"query_map", m.query_map}, {"ref_map", m.ref_map}, {"gt_scan_pairs", m.gt_scan_pairs},
                          {"stage", MissStageName(m.stage)}, {"detail", m.detail}});
    }
    return {{"closure_truth", {{"true", e.truth.num_true}, {"false", e.truth.num_false},
                               {"proximity_true", e.proximity_true}, {"proximity_false", e.proximity_false},
                               {"true_translation_m", config.true_translation}, {"true_rotation_deg", config.true_rotation_deg},
                               {"accepted", closures}}},
            {"revisit_coverage", {{"radius_m", config.revisit_radius}, {"gap_m", config.revisit_gap},
                                  {"revisit_scans", e.coverage.revisit_scans}, {"covered_scans", e.coverage.covered_scans},
                                  {"coverage", e.coverage.coverage},
                                  {"detector_covered_scans", e.detector_coverage.covered_scans},
                                  {"detector_coverage", e.detector_coverage.coverage}}},
            {"missed_revisits", {{"overlapping_map_pairs", e.missed.overlapping_pairs}, {"found_map_pairs", e.missed.found_pairs},
                                 {"funnel", {{"detector", FunnelJson(e.missed.detector, true)}, {"proximity", FunnelJson(e.missed.proximity, false)}}},
                                 {"per_stage", per_stage}, {"missed", missed}}}};
}

json TrajectoriesJson(const RunEvaluation& e) {
    return {{"odometry", TrajectoryJson(e.odometry)}, {"corrected", TrajectoryJson(e.corrected)}};
}

/// A partial reference: how many scans it pairs, and how much of the run the closure metrics cover.
json ReferenceJson(const RunEvaluation& e, std::size_t run_scans, std::size_t run_maps) {
    return {{"scans", run_scans}, {"paired_scans", e.reference_scans}, {"maps", run_maps},
            {"evaluated_maps", e.evaluated_maps}, {"evaluated_scans", e.evaluated_scans},
            {"left_out_closures", e.left_out_closures}, {"left_out_accepted_closures", e.left_out_accepted}};
}

void WriteJson(const fs::path& file, const json& content) {
    WriteJsonFile(file, content);
}

/// `extra`: more top-level keys (a partial reference's block).
void WriteMetrics(const RunFolder& run, const RunEvaluation& e, const json& verification, const json& extra) {
    json methods = json::array();
    for (const auto& m : e.methods) {
        methods.push_back({{"method", m.method}, {"precision", m.best.precision}, {"recall", m.best.recall},
                           {"f1", m.best.f1}, {"threshold", m.best.threshold},
                           {"recall_at_100_precision", m.has_full_precision ? json(m.recall_at_full_precision) : json(nullptr)},
                           {"ape_rmse_before_m", m.ape_rmse_before ? json(*m.ape_rmse_before) : json(nullptr)},
                           {"ape_rmse_after_m", m.ape_rmse_after ? json(*m.ape_rmse_after) : json(nullptr)}});
    }
    json metrics = {
        {"ground_truth", {{"segments", e.gt_segments}, {"closing_segment_pairs", e.gt_closing_segment_pairs}, {"scan_pairs", e.gt_scan_pairs},
                          {"tau_d_m", e.tau_d}, {"tau_d_source", e.tau_d_source},
                          {"scan_pairs_within_tau_d", e.gt_pairs_within_tau},
                          {"recall_ceiling", e.recall_ceiling()}}},
        {"methods", methods},
        {"map_level", {{"assessed_closures", e.map_metrics.closures.size()}, {"right_map_fraction", e.map_metrics.fraction_right},
                       {"translation_error_m", StatsJson(e.map_metrics.translation_error)},
                       {"yaw_error_deg", StatsJson(e.map_metrics.yaw_error_deg)},
                       {"maps_with_revisit", e.map_recall.maps_with_revisit}, {"maps_found_right", e.map_recall.maps_found_right},
                       {"map_recall", e.map_recall.recall}}},
        {"trajectory", TrajectoriesJson(e)}};
    metrics.update(verification);
    if (!extra.is_null()) metrics.update(extra);
    WriteJson(run.metrics_json(), metrics);
    for (const auto& [method, sweep] : e.sweeps) {
        WriteFileAtomically(run.root() / ("pr_curve_" + method + ".csv"),
                            [&sweep = sweep](std::ostream& out) { WritePrCurveCsv(out, sweep); });
    }
    WriteFileAtomically(run.root() / "comparison.md", [&e](std::ostream& out) { WriteComparisonTable(out, e.methods); });
}

/// The closure metrics of `state`, which has a reference pose for every scan; `e` holds the
/// trajectory metrics. `scans`: the run's scan at each of state's positions when `state` is the
/// part of a run its reference covers (CoveredRun), empty when it is the run itself.
void EvaluateClosures(const RunFolder& run, const RunState& state, const std::vector<std::size_t>& scans, std::size_t run_scans,
                      const RunOptions& options, const PipelineConfig& config, const json& extra, RunEvaluation& e,
                      EvaluationPass* chain, std::ostream& log) {
    std::string salt = state.dataset + "#" + std::to_string(options.from) + "#" + std::to_string(state.reference.size());
    for (const std::size_t scan : scans) salt += "," + std::to_string(scan);
    const std::string key = GroundTruthCacheKey(state.reference, config.ground_truth, salt);
    const fs::path cache_file = run.root() / "ground_truth_closures.txt";  // at the evaluated positions
    const auto cached = ReadCache(cache_file, key);
    // ScanContext's descriptors wait in an exclusive temporary of the run folder until the search (removed after).
    const DatasetPass pass = ReadDatasetPass(state.reference, scans, run_scans, options, config, cached,
                                             run.root(), chain, log);
    if (!cached) {
        WriteFileAtomically(cache_file, [&](std::ostream& out) { WriteGroundTruthClosures(out, pass.ground_truth, key); });
    }
    const auto& gt = pass.ground_truth;
    e.gt_segments = gt.segments.size();
    e.gt_closing_segment_pairs = gt.segment_pairs.size();
    e.gt_scan_pairs = gt.scan_pairs.size();
    const PredictedClosureConfig predicted = PredictionAtTheDataScale(config.predicted, gt, e);
    e.gt_pairs_within_tau = CountPairsWithinTau(gt.scan_pairs, state.reference, predicted);

    const auto density = ForEval(state, "density");
    e.sweeps["density"] = ScoreMapClosures(density, state.odometry, gt.scan_pairs, predicted);
    auto density_summary = SummarizeMethod("density maps", e.sweeps["density"]);
    density_summary.ape_rmse_before = e.odometry.ape.errors.translation_stats.rmse;
    density_summary.ape_rmse_after = e.corrected.ape.errors.translation_stats.rmse;
    e.methods.push_back(density_summary);
    if (config.output.elevation_ablation) {
        e.sweeps["elevation"] = ScoreMapClosures(ForEval(state, "elevation"), state.odometry, gt.scan_pairs, predicted);
        e.methods.push_back(SummarizeMethod("elevation maps", e.sweeps["elevation"]));
    }
    if (pass.scan_context && pass.scan_context->size() > 0) {
        // Each scan's ring-key search and its candidates: a minute at 100,000 scans.
        CountedProgress searched(log, Progress::DetectMode(options.quiet), "scans (ScanContext search)");
        const auto candidates =
            EvaluatedCandidates(SearchScanContext(*pass.scan_context, config.scan_context, std::ref(searched)), scans);
        e.sweeps["scan_context"] = ScoreScanContext(candidates, gt.scan_pairs);
        e.methods.push_back(SummarizeMethod("ScanContext", e.sweeps["scan_context"]));
    }
    MapMetricsConfig map_config;
    map_config.min_inliers = config.detector.min_inliers;
    e.map_metrics = EvaluateMapClosures(density, state.reference, gt.scan_pairs, map_config);
    std::vector<MapRange> ranges;
    for (const auto& m : state.maps) ranges.push_back({m.first_scan, m.last_scan});
    e.map_recall = ComputeMapRecall(ranges, density, gt.scan_pairs, map_config);
    std::vector<std::string> methods;
    const auto accepted = Accepted(state, methods);
    e.truth = JudgeClosures(accepted, state.reference, config.truth, state.odometry);
    for (std::size_t k = 0; k < accepted.size(); ++k) {
        if (methods[k] != "proximity") continue;
        ++(e.truth.verdicts[k].is_true ? e.proximity_true : e.proximity_false);
    }
    std::vector<std::pair<std::size_t, std::size_t>> true_pairs, true_detector_pairs;
    for (std::size_t k = 0; k < accepted.size(); ++k) {
        if (!e.truth.verdicts[k].is_true) continue;
        true_pairs.emplace_back(MapIndexOfScan(ranges, accepted[k].query_first_scan), MapIndexOfScan(ranges, accepted[k].ref_first_scan));
        if (methods[k] != "proximity") true_detector_pairs.push_back(true_pairs.back());
    }
    const auto revisits = FindRevisits(state.reference, config.truth.revisit_radius, config.truth.revisit_gap);
    e.coverage = ComputeRevisitCoverage(revisits, ranges, true_pairs);
    e.detector_coverage = ComputeRevisitCoverage(revisits, ranges, true_detector_pairs);
    e.missed = FindMissedRevisits(state, gt.scan_pairs, e.truth, config.detector.min_matches, config.detector.min_inliers);
    WriteMetrics(run, e, VerificationJson(e, accepted, methods, scans, config.truth), extra);
}

/// The reference covers some scans only: APE, RPE and the KITTI errors on those; the closure metrics
/// on the local maps it covers whole (each metric needs the reference pose of every scan of the maps
/// it judges), the closures with a map outside them left out and counted.
RunEvaluation EvaluatePartialReference(const RunFolder& run, const RunState& state, const RunOptions& options,
                                       const PipelineConfig& config, std::ostream& log) {
    Poses odometry, corrected;
    for (const std::size_t position : state.reference_scans) {
        odometry.push_back(state.odometry.at(position));
        corrected.push_back(state.corrected.at(position));
    }
    RunEvaluation e;
    e.reference_scans = state.reference_scans.size();
    e.odometry = EvaluateTrajectory(odometry, state.reference);
    e.corrected = EvaluateTrajectory(corrected, state.reference);
    const CoveredRun covered = CoverOfReference(state);
    e.left_out_closures = covered.left_out_closures;
    e.left_out_accepted = covered.left_out_accepted;
    log << "note: the reference covers " << e.reference_scans << " of " << state.odometry.size() << " scans: trajectory metrics on those; ";
    if (covered.state.odometry.size() < 2 || covered.state.maps.empty()) {
        e.closure_metrics = false;
        log << "no local map lies wholly within it, so no closure metrics\n";
        WriteJson(run.metrics_json(), {{"reference", ReferenceJson(e, state.odometry.size(), state.maps.size())},
                                       {"trajectory", TrajectoriesJson(e)}});
        return e;
    }
    e.evaluated_scans = covered.state.odometry.size();
    e.evaluated_maps = covered.state.maps.size();
    log << "closure metrics on the " << e.evaluated_scans << " scans of the " << e.evaluated_maps << " of "
        << state.maps.size() << " local maps it covers whole; " << e.left_out_closures
        << " closure candidates with a map outside them are left out\n";
    const json extra = {{"reference", ReferenceJson(e, state.odometry.size(), state.maps.size())}};
    EvaluateClosures(run, covered.state, covered.scans, state.odometry.size(), options, config, extra, e, nullptr, log);
    return e;
}

}  // namespace

std::optional<RunEvaluation> EvaluateRun(const RunFolder& run, const RunState& state, const RunOptions& options,
                                         const PipelineConfig& config, std::ostream& log, EvaluationPass* chain_pass) {
    if (state.has_partial_reference() && state.reference_scans.size() >= 2)
        return EvaluatePartialReference(run, state, options, config, log);
    if (!state.has_reference() || state.odometry.size() < 2) return std::nullopt;
    RunEvaluation e;
    e.reference_scans = e.evaluated_scans = state.reference.size();
    e.evaluated_maps = state.maps.size();
    e.odometry = EvaluateTrajectory(state.odometry, state.reference);
    e.corrected = EvaluateTrajectory(state.corrected, state.reference);
    EvaluateClosures(run, state, {}, state.odometry.size(), options, config, json(), e, chain_pass, log);
    return e;
}

}  // namespace revisit
