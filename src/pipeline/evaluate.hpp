#pragma once
/// Evaluation of a run (METHOD.md section 7): ground-truth closures (cached in the run folder),
/// PR sweeps of density maps, the elevation ablation and ScanContext on the same scan pairs,
/// map-level accuracy, and trajectory errors before and after correction.
#include <optional>
#include <ostream>

#include "evaluation/closure_truth.hpp"
#include "evaluation/method_comparison.hpp"
#include "evaluation/map_metrics.hpp"
#include "evaluation/trajectory_metrics.hpp"
#include "config/config.hpp"
#include "pipeline/missed_revisits.hpp"
#include "pipeline/pipeline.hpp"

namespace revisit {

struct TrajectoryEvaluation {
    ApeResult ape;
    PoseErrors rpe;
    KittiErrors kitti;
};

struct RunEvaluation {
    /// False when the reference covers no local map whole (a partial reference): then only the
    /// trajectory metrics are computed, on the scans it covers.
    bool closure_metrics = true;
    std::size_t reference_scans = 0;  ///< scans with a reference pose: the trajectory metrics' (all of a full reference)
    /// A partial reference (RunState::reference_scans): the closure metrics below are those of the local
    /// maps it covers whole (CoveredRun), their scans and closures; with a full reference, the whole run.
    std::size_t evaluated_scans = 0;
    std::size_t evaluated_maps = 0;
    std::size_t left_out_closures = 0;  ///< candidates (detector, proximity pass) with a map outside: not scored
    std::size_t left_out_accepted = 0;  ///< of those, closures of the final pose graph
    std::size_t gt_segments = 0;
    std::size_t gt_closing_segment_pairs = 0;
    std::size_t gt_scan_pairs = 0;
    std::size_t gt_pairs_within_tau = 0;  ///< of those, closer than tau_d by the reference: the recall ceiling
    double tau_d = 0.0;                   ///< [m] the prediction's pair range: evaluation.tau_d, or from the data
    std::string tau_d_source;             ///< "given", "overlap" (the ground truth's OverlapDistance), "paper" (6 m)
    /// The share of ground-truth pairs within tau_d: the most recall a map-level method can score.
    double recall_ceiling() const { return gt_scan_pairs ? double(gt_pairs_within_tau) / double(gt_scan_pairs) : 0.0; }
    std::map<std::string, PrSweepResult> sweeps;  ///< per method
    std::vector<MethodSummary> methods;
    MapMetrics map_metrics;
    MapRecall map_recall;
    ClosureTruth truth;          ///< the accepted closures that correct the trajectory, in run order
    std::size_t proximity_true = 0;   ///< of those, the proximity pass's (docs/method.md: at the end of the run)
    std::size_t proximity_false = 0;
    RevisitCoverage coverage;
    /// The same with the detector's closures alone: what place recognition finds without the
    /// proximity pass, which needs odometry good enough to lay the maps over each other.
    RevisitCoverage detector_coverage;
    MissedRevisits missed;
    TrajectoryEvaluation odometry;
    TrajectoryEvaluation corrected;
};

/// Everything above for a run with reference poses for every scan; when some scans have none, the
/// trajectory metrics on the others and the closure metrics on the maps it covers whole (nullopt
/// without any reference): re-reads the dataset once (only the scans the ground truth and ScanContext
/// need) unless `chain_pass` (RunPipeline's) holds every scan, writes metrics.json,
/// pr_curve_<method>.csv and comparison.md into the run folder.
std::optional<RunEvaluation> EvaluateRun(const RunFolder& run, const RunState& state, const RunOptions& options,
                                         const PipelineConfig& config, std::ostream& log, EvaluationPass* chain_pass = nullptr);

}  // namespace revisit
