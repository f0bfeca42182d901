#include "evaluation/method_comparison.hpp"

#include <algorithm>
#include <iomanip>
#include <map>
#include <ostream>
#include <sstream>
#include <utility>

namespace revisit {
namespace {

std::string Fixed(double value, int digits) {
    std::ostringstream text;
    text << std::fixed << std::setprecision(digits) << value;
    return text.str();
}

std::string OptionalFixed(const std::optional<double>& value, int digits) {
    return value ? Fixed(*value, digits) : std::string("-");
}

using ScanRange = std::pair<std::size_t, std::size_t>;  // first, last scan

/// The two maps a closure joins, in either order.
std::pair<ScanRange, ScanRange> MapPairOf(const MapClosureForEval& closure) {
    const ScanRange ref{closure.ref_first_scan, closure.ref_last_scan};
    const ScanRange query{closure.query_first_scan, closure.query_last_scan};
    return ref < query ? std::make_pair(ref, query) : std::make_pair(query, ref);
}

/// Whether any two of the closures' scan ranges are either the same or disjoint (a run's maps).
bool ScanRangesPartition(const std::vector<MapClosureForEval>& closures) {
    std::vector<ScanRange> ranges;
    for (const auto& c : closures) {
        ranges.push_back({c.ref_first_scan, c.ref_last_scan});
        ranges.push_back({c.query_first_scan, c.query_last_scan});
    }
    std::sort(ranges.begin(), ranges.end());
    ranges.erase(std::unique(ranges.begin(), ranges.end()), ranges.end());
    for (std::size_t k = 1; k < ranges.size(); ++k)
        if (ranges[k].first <= ranges[k - 1].second) return false;
    return true;
}

}  // namespace

PrSweepResult ScoreMapClosures(const std::vector<MapClosureForEval>& closures, const Poses& T_odom_sensor,
                               const std::vector<ScanPair>& ground_truth, const PredictedClosureConfig& config,
                               int min_inliers) {
    if (!ScanRangesPartition(closures)) {
        std::vector<ScoredPair> predicted = ExpandMapClosures(closures, T_odom_sensor, config);
        std::vector<double> thresholds = InlierThresholds(predicted, min_inliers);
        return SweepPrecisionRecall(std::move(predicted), ground_truth, thresholds, Acceptance::kScoreAtLeast);
    }
    // A run's maps partition its scans, so two closures predict a common scan pair only when they join
    // the same two maps: each map pair's closures are expanded and counted on their own, and the whole
    // prediction (tens of millions of pairs on a long drive) is never held at once.
    std::vector<ScanPair> storage;
    const std::vector<ScanPair>& truth = AsSortedUniquePairs(ground_truth, storage);
    std::vector<std::size_t> order(closures.size());
    for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return MapPairOf(closures[a]) < MapPairOf(closures[b]); });
    std::map<double, std::pair<std::size_t, std::size_t>> by_score;  // distinct pairs with this best score, true ones
    std::vector<MapClosureForEval> group;
    for (std::size_t k = 0; k < order.size();) {
        group.clear();
        const auto key = MapPairOf(closures[order[k]]);
        for (; k < order.size() && MapPairOf(closures[order[k]]) == key; ++k) group.push_back(closures[order[k]]);
        std::vector<ScoredPair> predicted = ExpandMapClosures(group, T_odom_sensor, config);
        KeepBestScorePerPair(predicted, Acceptance::kScoreAtLeast);
        for (const auto& scored : predicted) {
            auto& [count, true_count] = by_score[scored.score];
            ++count;
            true_count += std::binary_search(truth.begin(), truth.end(), scored.pair) ? 1 : 0;
        }
    }
    ThresholdCounts counts(InlierThresholdsUpTo(by_score.empty() ? 0.0 : by_score.rbegin()->first, min_inliers),
                           Acceptance::kScoreAtLeast);
    for (const auto& [score, count] : by_score) counts.Add(score, count.first, count.second);
    return counts.Result(truth.size());
}

PrSweepResult ScoreScanContext(const std::vector<ScanContextCandidate>& candidates,
                               const std::vector<ScanPair>& ground_truth, const ScanContextSweepConfig& config) {
    return SweepPrecisionRecall(ScanContextPairs(candidates), ground_truth,
                                RangeThresholds(config.first, config.last, config.step), Acceptance::kScoreAtMost);
}

MethodSummary SummarizeMethod(const std::string& method, const PrSweepResult& sweep) {
    MethodSummary summary;
    summary.method = method;
    summary.best = sweep.best;
    summary.has_full_precision = sweep.has_full_precision;
    summary.recall_at_full_precision = sweep.recall_at_full_precision;
    return summary;
}

void WritePrCurveCsv(std::ostream& out, const PrSweepResult& sweep) {
    out << "threshold,predicted,true_positives,ground_truth,precision,recall,f1\n";
    out << std::setprecision(10);
    for (const auto& p : sweep.curve)
        out << p.threshold << ',' << p.num_predicted << ',' << p.true_positives << ',' << p.num_ground_truth << ','
            << p.precision << ',' << p.recall << ',' << p.f1 << '\n';
}

void WriteComparisonTable(std::ostream& out, const std::vector<MethodSummary>& methods) {
    out << "| method | P | R | F1 | threshold | R@100%P | APE before [m] | APE after [m] |\n";
    out << "|---|---|---|---|---|---|---|---|\n";
    for (const auto& m : methods) {
        out << "| " << m.method << " | " << Fixed(m.best.precision, 3) << " | " << Fixed(m.best.recall, 3) << " | "
            << Fixed(m.best.f1, 3) << " | " << Fixed(m.best.threshold, 2) << " | "
            << (m.has_full_precision ? Fixed(m.recall_at_full_precision, 3) : std::string("-")) << " | "
            << OptionalFixed(m.ape_rmse_before, 2) << " | " << OptionalFixed(m.ape_rmse_after, 2) << " |\n";
    }
}

}  // namespace revisit
