#pragma once
/// Scoring any closure method against the same ground truth, and the side-by-side table
/// (issue 7: method x (P, R, F1, recall@100%P, APE before/after); METHOD.md section 7, Table I).
#include "core/trajectory.hpp"
#include "evaluation/map_closure.hpp"
#include "evaluation/pr_sweep.hpp"
#include "evaluation/predicted_closures.hpp"
#include "evaluation/scan_context.hpp"

#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

namespace revisit {

/// Map closures (density or elevation images alike) expanded with tau_d and swept over inliers from
/// `min_inliers` to the maximum seen.
PrSweepResult ScoreMapClosures(const std::vector<MapClosureForEval>& closures, const Poses& T_odom_sensor,
                               const std::vector<ScanPair>& ground_truth, const PredictedClosureConfig& config,
                               int min_inliers = 3);

struct ScanContextSweepConfig {
    double first = 0.10;  ///< distance thresholds swept, as the thesis' evaluation (0.1 .. 0.95)
    double last = 0.95;
    double step = 0.01;
};

/// ScanContext candidates (all kept per query) swept over distance thresholds, accepted at or below.
PrSweepResult ScoreScanContext(const std::vector<ScanContextCandidate>& candidates,
                               const std::vector<ScanPair>& ground_truth, const ScanContextSweepConfig& config = {});

struct MethodSummary {
    std::string method;                     ///< e.g. "density maps", "elevation maps", "ScanContext"
    PrPoint best;                           ///< P, R, F1 and threshold at maximum F1
    bool has_full_precision = false;
    double recall_at_full_precision = 0.0;
    std::optional<double> ape_rmse_before;  ///< [m] APE translation RMSE of the odometry
    std::optional<double> ape_rmse_after;   ///< [m] APE translation RMSE with this method's closures
};

MethodSummary SummarizeMethod(const std::string& method, const PrSweepResult& sweep);

/// CSV with a header: threshold,predicted,true_positives,ground_truth,precision,recall,f1.
void WritePrCurveCsv(std::ostream& out, const PrSweepResult& sweep);

/// Markdown table, one row per method: method | P | R | F1 | threshold | R@100%P | APE before | APE after.
/// Missing values print as "-".
void WriteComparisonTable(std::ostream& out, const std::vector<MethodSummary>& methods);

}  // namespace revisit
