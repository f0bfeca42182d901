#include "evaluation/pr_sweep.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

namespace revisit {
namespace {

// Four true closures; five predictions, three of them right, scored by inliers.
std::vector<ScanPair> Truth() { return {{1, 10}, {2, 11}, {3, 12}, {4, 13}}; }
std::vector<ScoredPair> Predicted() {
    return {{{1, 10}, 20}, {{2, 11}, 15}, {{5, 20}, 12}, {{3, 12}, 8}, {{6, 30}, 4}};
}

TEST(SweepPrecisionRecall, MatchesHandComputedCurve) {
    const auto predicted = Predicted();
    const auto thresholds = InlierThresholds(predicted);
    ASSERT_EQ(thresholds.size(), 18u);  // 3 .. 20
    const auto result = SweepPrecisionRecall(predicted, Truth(), thresholds, Acceptance::kScoreAtLeast);
    ASSERT_EQ(result.curve.size(), 18u);
    // threshold 3: 5 predicted, 3 right: P = 3/5, R = 3/4, F1 = 2/3.
    EXPECT_EQ(result.curve[0].num_predicted, 5u);
    EXPECT_EQ(result.curve[0].true_positives, 3u);
    EXPECT_NEAR(result.curve[0].precision, 0.6, 1e-12);
    EXPECT_NEAR(result.curve[0].recall, 0.75, 1e-12);
    EXPECT_NEAR(result.curve[0].f1, 2.0 / 3.0, 1e-12);
    // threshold 9: (1,10), (2,11), (5,20): P = 2/3, R = 1/2, F1 = 4/7.
    EXPECT_NEAR(result.curve[6].precision, 2.0 / 3.0, 1e-12);
    EXPECT_NEAR(result.curve[6].recall, 0.5, 1e-12);
    EXPECT_NEAR(result.curve[6].f1, 4.0 / 7.0, 1e-12);
    // threshold 16: only (1,10): P = 1, R = 1/4.
    EXPECT_NEAR(result.curve[13].precision, 1.0, 1e-12);
    EXPECT_NEAR(result.curve[13].recall, 0.25, 1e-12);
    // Max F1 = 0.75 at threshold 5 (P = R = 3/4); recall at 100% precision = 1/2 from threshold 13.
    EXPECT_DOUBLE_EQ(result.best.threshold, 5.0);
    EXPECT_NEAR(result.best.f1, 0.75, 1e-12);
    EXPECT_NEAR(result.best.precision, 0.75, 1e-12);
    EXPECT_NEAR(result.best.recall, 0.75, 1e-12);
    ASSERT_TRUE(result.has_full_precision);
    EXPECT_NEAR(result.recall_at_full_precision, 0.5, 1e-12);
    EXPECT_DOUBLE_EQ(result.threshold_at_full_precision, 13.0);
}

TEST(SweepPrecisionRecall, InvariantToOrderSwapsAndRepeats) {
    const auto thresholds = InlierThresholds(Predicted());
    const auto reference = SweepPrecisionRecall(Predicted(), Truth(), thresholds, Acceptance::kScoreAtLeast);

    auto predicted = Predicted();
    for (auto& scored : predicted) std::swap(scored.pair.first, scored.pair.second);  // unsorted pairs
    predicted.push_back({{10, 1}, 3});   // a repeat with a worse score must not lower (1,10)'s score
    predicted.push_back({{12, 3}, 5});
    auto truth = Truth();
    truth.push_back({13, 4});  // duplicate, reversed
    std::mt19937 rng(3);
    std::shuffle(predicted.begin(), predicted.end(), rng);
    std::shuffle(truth.begin(), truth.end(), rng);
    const auto shuffled = SweepPrecisionRecall(predicted, truth, thresholds, Acceptance::kScoreAtLeast);

    ASSERT_EQ(shuffled.curve.size(), reference.curve.size());
    for (std::size_t k = 0; k < reference.curve.size(); ++k) {
        EXPECT_EQ(shuffled.curve[k].num_predicted, reference.curve[k].num_predicted) << k;
        EXPECT_EQ(shuffled.curve[k].true_positives, reference.curve[k].true_positives) << k;
        EXPECT_EQ(shuffled.curve[k].num_ground_truth, 4u);
        EXPECT_DOUBLE_EQ(shuffled.curve[k].f1, reference.curve[k].f1) << k;
    }
    EXPECT_DOUBLE_EQ(shuffled.recall_at_full_precision, reference.recall_at_full_precision);
}

TEST(SweepPrecisionRecall, DistancesAcceptBelowThreshold) {
    // ScanContext-like scores: lower is better.
    const std::vector<ScoredPair> predicted = {{{1, 10}, 0.05}, {{5, 20}, 0.2}, {{2, 11}, 0.3}, {{6, 30}, 0.6}};
    const auto result = SweepPrecisionRecall(predicted, Truth(), RangeThresholds(0.1, 0.7, 0.1), Acceptance::kScoreAtMost);
    ASSERT_EQ(result.curve.size(), 7u);
    EXPECT_EQ(result.curve[0].num_predicted, 1u);  // <= 0.1
    EXPECT_NEAR(result.curve[0].precision, 1.0, 1e-12);
    EXPECT_EQ(result.curve[2].num_predicted, 3u);  // <= 0.3
    EXPECT_NEAR(result.curve[2].recall, 0.5, 1e-12);
    EXPECT_NEAR(result.curve[2].precision, 2.0 / 3.0, 1e-12);
    EXPECT_NEAR(result.curve[6].precision, 0.5, 1e-12);
    EXPECT_NEAR(result.recall_at_full_precision, 0.25, 1e-12);
    EXPECT_NEAR(result.best.f1, 2 * (2.0 / 3) * 0.5 / (2.0 / 3 + 0.5), 1e-12);
}

TEST(SweepPrecisionRecall, EachThresholdScoredAsGivenInAnyOrderTiesAccepted) {
    // Thresholds out of order and repeated get the same point as in order; a score equal to the
    // threshold is accepted either way (>= for inliers, <= for distances).
    const std::vector<double> inliers = {20, 3, 15, 15, 8, 21};
    const auto at_least = SweepPrecisionRecall(Predicted(), Truth(), inliers, Acceptance::kScoreAtLeast);
    const std::vector<std::size_t> predicted_at_least = {1, 5, 2, 2, 4, 0}, true_at_least = {1, 3, 2, 2, 3, 0};
    const std::vector<ScoredPair> distances = {{{1, 10}, 0.25}, {{5, 20}, 0.5}, {{2, 11}, 0.75}};
    const std::vector<double> limits = {0.75, 0.0, 0.5, 0.25, 0.5};
    const auto at_most = SweepPrecisionRecall(distances, Truth(), limits, Acceptance::kScoreAtMost);
    const std::vector<std::size_t> predicted_at_most = {3, 0, 2, 1, 2}, true_at_most = {2, 0, 1, 1, 1};
    ASSERT_EQ(at_least.curve.size(), inliers.size());
    ASSERT_EQ(at_most.curve.size(), limits.size());
    for (std::size_t k = 0; k < inliers.size(); ++k) {
        EXPECT_EQ(at_least.curve[k].threshold, inliers[k]);
        EXPECT_EQ(at_least.curve[k].num_predicted, predicted_at_least[k]) << inliers[k];
        EXPECT_EQ(at_least.curve[k].true_positives, true_at_least[k]) << inliers[k];
    }
    for (std::size_t k = 0; k < limits.size(); ++k) {
        EXPECT_EQ(at_most.curve[k].num_predicted, predicted_at_most[k]) << limits[k];
        EXPECT_EQ(at_most.curve[k].true_positives, true_at_most[k]) << limits[k];
    }
}

TEST(SweepPrecisionRecall, NothingPredictedGivesZeros) {
    const auto result = SweepPrecisionRecall({}, Truth(), {3.0, 4.0}, Acceptance::kScoreAtLeast);
    EXPECT_EQ(result.best.f1, 0.0);
    EXPECT_FALSE(result.has_full_precision);
    EXPECT_EQ(result.curve[0].num_ground_truth, 4u);
}

TEST(RangeThresholds, CoversScanContextSweepWithoutDrift) {
    const auto thresholds = RangeThresholds(0.10, 0.95, 0.01);
    ASSERT_EQ(thresholds.size(), 86u);
    EXPECT_NEAR(thresholds.back(), 0.95, 1e-12);
}

TEST(AsSortedUniquePairs, TakesACanonicalListAsItIsAndSortsAnyOther) {
    const std::vector<ScanPair> canonical = {{0, 5}, {0, 7}, {2, 2}, {3, 9}};
    std::vector<ScanPair> storage;
    EXPECT_EQ(&AsSortedUniquePairs(canonical, storage), &canonical);  // not copied
    EXPECT_TRUE(storage.empty());
    // Reversed, repeated or out of order: sorted like SortedUniquePairs.
    for (const std::vector<ScanPair>& other : {std::vector<ScanPair>{{5, 0}, {0, 7}, {2, 2}, {9, 3}},
                                               std::vector<ScanPair>{{0, 5}, {0, 5}, {0, 7}, {2, 2}, {3, 9}},
                                               std::vector<ScanPair>{{3, 9}, {0, 5}, {2, 2}, {0, 7}}}) {
        const std::vector<ScanPair>& sorted = AsSortedUniquePairs(other, storage);
        EXPECT_EQ(&sorted, &storage);
        EXPECT_EQ(sorted, canonical);
        EXPECT_EQ(sorted, SortedUniquePairs(other));
    }
}

}  // namespace
}  // namespace revisit
