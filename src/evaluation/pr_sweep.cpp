#include "evaluation/pr_sweep.hpp"

#include "core/error.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace revisit {

ThresholdCounts::ThresholdCounts(std::vector<double> thresholds, Acceptance acceptance)
    : thresholds_(std::move(thresholds)), sorted_(thresholds_), acceptance_(acceptance) {
    std::sort(sorted_.begin(), sorted_.end());
    predicted_at_.assign(sorted_.size() + 1, 0);
    true_at_.assign(sorted_.size() + 1, 0);
}

void ThresholdCounts::Add(double score, std::size_t count, std::size_t true_count) {
    // The thresholds accepting a score are a run of the sorted ones: at least, [0, bound) (those up to
    // the score); at most, [bound, T) (those from it). Counted at `bound`, summed per threshold below.
    const auto bound = acceptance_ == Acceptance::kScoreAtLeast ? std::upper_bound(sorted_.begin(), sorted_.end(), score)
                                                                 : std::lower_bound(sorted_.begin(), sorted_.end(), score);
    const auto at = static_cast<std::size_t>(bound - sorted_.begin());
    predicted_at_[at] += count;
    true_at_[at] += true_count;
}

PrSweepResult ThresholdCounts::Result(std::size_t num_ground_truth) const {
    const bool high_first = acceptance_ == Acceptance::kScoreAtLeast;
    const std::size_t num_sorted = sorted_.size();
    std::vector<std::size_t> accepted(num_sorted, 0), accepted_true(num_sorted, 0);
    std::size_t running = 0, running_true = 0;
    for (std::size_t step = 0; step < num_sorted; ++step) {
        // At least: threshold i accepts the runs ending after it, so sum from the highest down.
        const std::size_t i = high_first ? num_sorted - 1 - step : step;
        running += predicted_at_[high_first ? i + 1 : i];
        running_true += true_at_[high_first ? i + 1 : i];
        accepted[i] = running;
        accepted_true[i] = running_true;
    }
    PrSweepResult result;
    result.curve.reserve(thresholds_.size());
    for (const double threshold : thresholds_) {
        const auto i = static_cast<std::size_t>(std::lower_bound(sorted_.begin(), sorted_.end(), threshold) - sorted_.begin());
        PrPoint point;
        point.threshold = threshold;
        point.num_predicted = accepted[i];
        point.true_positives = accepted_true[i];
        point.num_ground_truth = num_ground_truth;
        if (point.num_predicted > 0) point.precision = double(point.true_positives) / double(point.num_predicted);
        if (num_ground_truth > 0) point.recall = double(point.true_positives) / double(num_ground_truth);
        if (point.precision + point.recall > 0.0)
            point.f1 = 2.0 * point.precision * point.recall / (point.precision + point.recall);
        if (result.curve.empty() || point.f1 > result.best.f1) result.best = point;
        if (point.num_predicted > 0 && point.true_positives == point.num_predicted &&
            (!result.has_full_precision || point.recall > result.recall_at_full_precision)) {
            result.has_full_precision = true;
            result.recall_at_full_precision = point.recall;
            result.threshold_at_full_precision = threshold;
        }
        result.curve.push_back(point);
    }
    return result;
}

void KeepBestScorePerPair(std::vector<ScoredPair>& predicted, Acceptance acceptance) {
    const bool high_first = acceptance == Acceptance::kScoreAtLeast;
    for (auto& scored : predicted) scored.pair = MakeScanPair(scored.pair.first, scored.pair.second);
    std::sort(predicted.begin(), predicted.end(), [high_first](const ScoredPair& a, const ScoredPair& b) {
        if (a.pair != b.pair) return a.pair < b.pair;
        return high_first ? a.score > b.score : a.score < b.score;
    });
    predicted.erase(std::unique(predicted.begin(), predicted.end(),
                                [](const ScoredPair& a, const ScoredPair& b) { return a.pair == b.pair; }),
                    predicted.end());
}

PrSweepResult SweepPrecisionRecall(std::vector<ScoredPair> predicted, const std::vector<ScanPair>& ground_truth,
                                   const std::vector<double>& thresholds, Acceptance acceptance) {
    // Sorted vectors, not hash containers: a node per pair was the evaluation's memory peak.
    std::vector<ScanPair> storage;
    const std::vector<ScanPair>& truth = AsSortedUniquePairs(ground_truth, storage);
    KeepBestScorePerPair(predicted, acceptance);
    ThresholdCounts counts(thresholds, acceptance);
    for (std::size_t k = 0, t = 0; k < predicted.size(); ++k) {  // one merge with the sorted truth
        while (t < truth.size() && truth[t] < predicted[k].pair) ++t;
        counts.Add(predicted[k].score, 1, t < truth.size() && truth[t] == predicted[k].pair ? 1 : 0);
    }
    return counts.Result(truth.size());
}

std::vector<double> InlierThresholds(const std::vector<ScoredPair>& predicted, int min_inliers) {
    double max_score = min_inliers;
    for (const auto& scored : predicted) max_score = std::max(max_score, scored.score);
    return InlierThresholdsUpTo(max_score, min_inliers);
}

std::vector<double> InlierThresholdsUpTo(double max_score, int min_inliers) {
    max_score = std::max<double>(max_score, min_inliers);
    std::vector<double> thresholds;
    for (int inliers = min_inliers; inliers <= static_cast<int>(std::floor(max_score)); ++inliers)
        thresholds.push_back(inliers);
    return thresholds;
}

std::vector<double> RangeThresholds(double first, double last, double step) {
    if (!(step > 0.0)) throw ConfigError("RangeThresholds: step must be positive");
    std::vector<double> thresholds;
    for (std::size_t k = 0;; ++k) {
        const double value = first + static_cast<double>(k) * step;  // no accumulated rounding
        if (value > last + step * 1e-3) break;
        thresholds.push_back(value);
    }
    return thresholds;
}

}  // namespace revisit
