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
