#pragma once
/// Precision, recall and F1 of scan-level closures over a sweep of acceptance thresholds
/// (METHOD.md section 7, "Predicted closures" step 3; thesis section 5.1).
#include "evaluation/scan_pair.hpp"

#include <cstddef>
#include <vector>

namespace revisit {

/// How a threshold accepts a score: inliers are accepted when high, descriptor distances when low.
enum class Acceptance { kScoreAtLeast, kScoreAtMost };

struct PrPoint {
    double threshold = 0.0;
    std::size_t num_predicted = 0;     ///< distinct scan pairs accepted at this threshold
    std::size_t true_positives = 0;
    std::size_t num_ground_truth = 0;  ///< distinct ground-truth scan pairs
    double precision = 0.0;            ///< TP / predicted; 0 when nothing is predicted
    double recall = 0.0;               ///< TP / ground truth; 0 when there is no ground truth
    double f1 = 0.0;                   ///< 2 P R / (P + R); 0 when P + R = 0
};

struct PrSweepResult {
    std::vector<PrPoint> curve;           ///< one point per threshold, in the given order
    PrPoint best;                         ///< the point of maximum F1 (first one on ties)
    bool has_full_precision = false;      ///< some threshold predicts pairs that are all correct
    double recall_at_full_precision = 0;  ///< highest recall among thresholds with precision 1 (and >= 1 prediction)
    double threshold_at_full_precision = 0;
};

/// Distinct predictions counted by the thresholds that accept them: a sweep that never holds every
/// predicted pair at once (a long drive's map closures predict tens of millions). Each prediction is
/// added once, with its best score.
class ThresholdCounts {
  public:
    ThresholdCounts(std::vector<double> thresholds, Acceptance acceptance);
    /// `count` distinct predictions with this score, `true_count` of them in the ground truth.
    void Add(double score, std::size_t count, std::size_t true_count);
    /// The curve over the thresholds in the order given, against `num_ground_truth` distinct pairs.
    PrSweepResult Result(std::size_t num_ground_truth) const;

  private:
    std::vector<double> thresholds_;  // as given
    std::vector<double> sorted_;      // ascending
    Acceptance acceptance_;
    std::vector<std::size_t> predicted_at_, true_at_;  // by where the accepting run of sorted_ starts or ends
};

/// Each pair once, in MakeScanPair's order, with its best score under `acceptance`; sorted by pair.
void KeepBestScorePerPair(std::vector<ScoredPair>& predicted, Acceptance acceptance);

/// Sweeps `thresholds`. A pair predicted several times keeps its best score, so the result does not
/// depend on the order or repetition of the input pairs (predicted or ground truth).
/// `predicted` is taken by value and reordered in place: pass it with std::move when it is not needed after.
PrSweepResult SweepPrecisionRecall(std::vector<ScoredPair> predicted, const std::vector<ScanPair>& ground_truth,
                                   const std::vector<double>& thresholds, Acceptance acceptance);

/// Integer thresholds from `min_inliers` to the largest score seen (METHOD.md: "inliers from 3 to the
/// maximum seen"); just {min_inliers} when no score reaches it.
std::vector<double> InlierThresholds(const std::vector<ScoredPair>& predicted, int min_inliers = 3);
/// The same for a largest score known beforehand.
std::vector<double> InlierThresholdsUpTo(double max_score, int min_inliers = 3);

/// first, first + step, ... up to last inclusive (within step / 1000), e.g. ScanContext's 0.10 .. 0.95.
std::vector<double> RangeThresholds(double first, double last, double step);

}  // namespace revisit
