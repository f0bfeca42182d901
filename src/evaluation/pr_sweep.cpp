#include "evaluation/pr_sweep.hpp"

#include "core/error.hpp"

#include <algorithm>
#include <cmath>
#include <unordered_map>
#include <unordered_set>

namespace revisit {
namespace {

/// One entry per distinct pair with its best score under `acceptance`.
std::vector<ScoredPair> BestScorePerPair(const std::vector<ScoredPair>& predicted, Acceptance acceptance) {
    std::unordered_map<ScanPair, double, ScanPairHash> best;
    for (const auto& scored : predicted) {
        const ScanPair pair = MakeScanPair(scored.pair.first, scored.pair.second);
        const auto [it, inserted] = best.emplace(pair, scored.score);
        if (inserted) continue;
        it->second = acceptance == Acceptance::kScoreAtLeast ? std::max(it->second, scored.score)
                                                              : std::min(it->second, scored.score);
    }
    std::vector<ScoredPair> unique;
    unique.reserve(best.size());
    for (const auto& [pair, score] : best) unique.push_back({pair, score});
    return unique;
}

}  // namespace

PrSweepResult SweepPrecisionRecall(const std::vector<ScoredPair>& predicted, const std::vector<ScanPair>& ground_truth,
                                   const std::vector<double>& thresholds, Acceptance acceptance) {
    std::unordered_set<ScanPair, ScanPairHash> truth;
    for (const auto& pair : ground_truth) truth.insert(MakeScanPair(pair.first, pair.second));

    // Sort the distinct predictions from most to least confident; a threshold then accepts a prefix,
    // and a running count of true positives answers every threshold by binary search.
    std::vector<ScoredPair> unique = BestScorePerPair(predicted, acceptance);
    const bool high_first = acceptance == Acceptance::kScoreAtLeast;
    std::sort(unique.begin(), unique.end(), [high_first](const ScoredPair& a, const ScoredPair& b) {
        if (a.score != b.score) return high_first ? a.score > b.score : a.score < b.score;
        return a.pair < b.pair;
    });
    std::vector<std::size_t> cumulative_tp(unique.size() + 1, 0);
    for (std::size_t k = 0; k < unique.size(); ++k)
        cumulative_tp[k + 1] = cumulative_tp[k] + (truth.count(unique[k].pair) ? 1 : 0);

    PrSweepResult result;
    result.curve.reserve(thresholds.size());
    for (const double threshold : thresholds) {
        const auto end = high_first
            ? std::partition_point(unique.begin(), unique.end(), [&](const ScoredPair& s) { return s.score >= threshold; })
            : std::partition_point(unique.begin(), unique.end(), [&](const ScoredPair& s) { return s.score <= threshold; });
        PrPoint point;
        point.threshold = threshold;
        point.num_predicted = static_cast<std::size_t>(end - unique.begin());
        point.true_positives = cumulative_tp[point.num_predicted];
        point.num_ground_truth = truth.size();
        if (point.num_predicted > 0) point.precision = double(point.true_positives) / double(point.num_predicted);
        if (!truth.empty()) point.recall = double(point.true_positives) / double(truth.size());
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

std::vector<double> InlierThresholds(const std::vector<ScoredPair>& predicted, int min_inliers) {
    double max_score = min_inliers;
    for (const auto& scored : predicted) max_score = std::max(max_score, scored.score);
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
