#include "evaluation/method_comparison.hpp"

#include "core/se3.hpp"

#include <gtest/gtest.h>

#include <sstream>

namespace revisit {
namespace {

TEST(ScoreMapClosures, ExpandsAndSweepsInliers) {
    // Straight 1 m steps; the query map (scans 100-104) truly revisits the reference map (scans 0-4)
    // at the same place; a second, wrong closure (10 inliers) points at scans 50-54.
    Poses odometry;
    for (int i = 0; i < 105; ++i) odometry.push_back(PoseFromXYZRPY(i < 100 ? i : i - 100, 0, 0, 0, 0, 0));
    std::vector<ScanPair> truth;
    for (std::size_t i = 0; i < 5; ++i) truth.push_back({i, 100 + i});
    MapClosureForEval right;
    right.query_first_scan = 100;
    right.query_last_scan = 104;
    right.ref_first_scan = 0;
    right.ref_last_scan = 4;
    right.inliers = 25;
    MapClosureForEval wrong = right;
    wrong.ref_first_scan = 50;
    wrong.ref_last_scan = 54;
    wrong.inliers = 10;
    PredictedClosureConfig config;
    config.max_distance = 0.5;  // only scans at the same offset in both maps
    const auto sweep = ScoreMapClosures({wrong, right}, odometry, truth, config);
    ASSERT_EQ(sweep.curve.size(), 23u);  // 3 .. 25
    EXPECT_NEAR(sweep.curve[0].precision, 0.5, 1e-12);  // 10 predicted, 5 right
    EXPECT_NEAR(sweep.best.f1, 1.0, 1e-12);
    EXPECT_DOUBLE_EQ(sweep.best.threshold, 11.0);
    EXPECT_NEAR(sweep.recall_at_full_precision, 1.0, 1e-12);

    MethodSummary summary = SummarizeMethod("density maps", sweep);
    summary.ape_rmse_before = 14.64;
    std::ostringstream table;
    WriteComparisonTable(table, {summary});
    EXPECT_NE(table.str().find("| density maps | 1.000 | 1.000 | 1.000 | 11.00 | 1.000 | 14.64 | - |"), std::string::npos)
        << table.str();
    std::ostringstream csv;
    WritePrCurveCsv(csv, sweep);
    EXPECT_EQ(csv.str().substr(0, csv.str().find('\n')), "threshold,predicted,true_positives,ground_truth,precision,recall,f1");
    EXPECT_NE(csv.str().find("\n3,10,5,5,0.5,1,0.6666666667\n"), std::string::npos) << csv.str();
}

TEST(ScoreMapClosures, OneMapPairAtATimeGivesTheCurveOfTheWholePrediction) {
    // A loop of 1 m steps around a 40 m square driven twice: maps of 10 scans; closures between the
    // laps (right, shifted, repeated with other inliers, in either order) and one between two maps of
    // the first lap. Counting map pair by map pair must give the curve of all pairs expanded at once.
    Poses odometry;
    for (int i = 0; i < 320; ++i) {
        const int k = i % 160, side = k / 40, along = k % 40;
        const double x = side == 0 ? along : side == 1 ? 40 : side == 2 ? 40 - along : 0;
        const double y = side == 0 ? 0 : side == 1 ? along : side == 2 ? 40 : 40 - along;
        odometry.push_back(PoseFromXYZRPY(x, y, 0, 0, 0, 0));
    }
    const auto closure = [](std::size_t ref_map, std::size_t query_map, double shift, double inliers) {
        MapClosureForEval c;
        c.ref_first_scan = 10 * ref_map;
        c.ref_last_scan = c.ref_first_scan + 9;
        c.query_first_scan = 10 * query_map;
        c.query_last_scan = c.query_first_scan + 9;
        c.T_query_ref = PoseFromXYZRPY(shift, 0, 0, 0, 0, 0);
        c.inliers = inliers;
        return c;
    };
    std::vector<MapClosureForEval> closures;
    for (std::size_t m = 0; m < 16; ++m) closures.push_back(closure(m, m + 16, 0.0, 5.0 + m));
    closures.push_back(closure(3, 19, 4.0, 30.0));   // the same maps again, shifted, more inliers
    closures.push_back(closure(20, 4, 0.0, 7.0));    // reversed roles
    closures.push_back(closure(5, 8, 0.0, 12.0));    // no revisit: all its pairs false
    std::vector<ScanPair> truth;
    for (std::size_t s = 0; s < 160; s += 2) truth.push_back({s, s + 160});
    PredictedClosureConfig config;
    config.max_distance = 3.0;
    const auto expanded = ExpandMapClosures(closures, odometry, config);
    ASSERT_GT(expanded.size(), 500u);
    const auto whole = SweepPrecisionRecall(expanded, truth, InlierThresholds(expanded), Acceptance::kScoreAtLeast);
    const auto per_map_pair = ScoreMapClosures(closures, odometry, truth, config);
    ASSERT_EQ(per_map_pair.curve.size(), whole.curve.size());
    for (std::size_t k = 0; k < whole.curve.size(); ++k) {
        EXPECT_EQ(per_map_pair.curve[k].threshold, whole.curve[k].threshold);
        EXPECT_EQ(per_map_pair.curve[k].num_predicted, whole.curve[k].num_predicted) << k;
        EXPECT_EQ(per_map_pair.curve[k].true_positives, whole.curve[k].true_positives) << k;
    }
    EXPECT_EQ(per_map_pair.best.f1, whole.best.f1);
    // Scan ranges that overlap (not a run's maps) take the whole expansion: the same curve again.
    closures.push_back(closure(0, 17, 0.0, 9.0));
    closures.back().ref_last_scan = 14;
    const auto overlapping = ExpandMapClosures(closures, odometry, config);
    const auto whole_overlapping = SweepPrecisionRecall(overlapping, truth, InlierThresholds(overlapping), Acceptance::kScoreAtLeast);
    const auto scored_overlapping = ScoreMapClosures(closures, odometry, truth, config);
    ASSERT_EQ(scored_overlapping.curve.size(), whole_overlapping.curve.size());
    for (std::size_t k = 0; k < whole_overlapping.curve.size(); ++k)
        EXPECT_EQ(scored_overlapping.curve[k].true_positives, whole_overlapping.curve[k].true_positives) << k;
}

TEST(ScoreScanContext, SweepsDistancesAtOrBelow) {
    const std::vector<ScanContextCandidate> candidates = {{60, 2, 0.12, 0}, {60, 30, 0.4, 3}, {70, 5, 0.2, 1}};
    const std::vector<ScanPair> truth = {{2, 60}, {5, 70}};
    const auto sweep = ScoreScanContext(candidates, truth);
    ASSERT_EQ(sweep.curve.size(), 86u);
    EXPECT_EQ(sweep.curve[0].num_predicted, 0u);  // 0.10
    EXPECT_NEAR(sweep.best.f1, 1.0, 1e-12);       // 0.20 .. 0.39
    EXPECT_NEAR(sweep.best.threshold, 0.20, 1e-12);
    EXPECT_NEAR(sweep.curve.back().precision, 2.0 / 3.0, 1e-12);
}

}  // namespace
}  // namespace revisit
