#include "evaluation/map_metrics.hpp"
#include "evaluation/predicted_closures.hpp"

#include "core/error.hpp"
#include "core/se3.hpp"

#include <gtest/gtest.h>

#include <algorithm>

namespace revisit {
namespace {

constexpr double kPi = 3.14159265358979323846;

/// Odometry of 13 scans: a reference map (scans 0-2) and a query map (scans 10-12), each driving 1 m per
/// scan along its own x axis; the odometry frames of the two maps differ (drift), which must not matter.
Poses Odometry() {
    Poses poses(13, Eigen::Isometry3d::Identity());
    const Eigen::Isometry3d ref_origin = PoseFromXYZRPY(5.0, -3.0, 0.2, 0.0, 0.0, 0.8);
    const Eigen::Isometry3d query_origin = PoseFromXYZRPY(-40.0, 60.0, 1.0, 0.0, 0.0, -2.0);
    for (int k = 0; k < 3; ++k) {
        poses[k] = ref_origin * PoseFromXYZRPY(k, 0, 0, 0, 0, 0);
        poses[10 + k] = query_origin * PoseFromXYZRPY(k, 0, 0, 0, 0, 0);
    }
    return poses;
}

MapClosureForEval Closure(const Eigen::Isometry3d& T_query_ref, double inliers) {
    MapClosureForEval closure;
    closure.query_first_scan = 10;
    closure.query_last_scan = 12;
    closure.ref_first_scan = 0;
    closure.ref_last_scan = 2;
    closure.T_query_ref = T_query_ref;
    closure.inliers = inliers;
    return closure;
}

TEST(ExpandMapClosures, PairsCloserThanTauAfterCorrection) {
    // The reference map sits 3 m to the left of the query map: distances sqrt((r - q)^2 + 9).
    const auto closure = Closure(PoseFromXYZRPY(0, 3, 0, 0, 0, 0), 17);
    PredictedClosureConfig config;
    config.max_distance = 3.5;  // |r - q| <= 1
    auto pairs = ExpandMapClosures({closure}, Odometry(), config);
    std::vector<ScanPair> got;
    for (const auto& scored : pairs) {
        EXPECT_EQ(scored.score, 17.0);
        got.push_back(scored.pair);
    }
    std::sort(got.begin(), got.end());
    const std::vector<ScanPair> expected = {{0, 10}, {0, 11}, {1, 10}, {1, 11}, {1, 12}, {2, 11}, {2, 12}};
    EXPECT_EQ(got, expected);
    config.max_distance = 3.0;  // strictly closer: none
    EXPECT_TRUE(ExpandMapClosures({closure}, Odometry(), config).empty());
    config.max_distance = 6.0;  // tau_d of the paper: all nine
    EXPECT_EQ(ExpandMapClosures({closure}, Odometry(), config).size(), 9u);
}

TEST(ExpandMapClosures, UsesTheRelativePoseDirection) {
    // Rotating the reference map by 180 degrees about its origin puts scan r at -r: only (0, 10) within 0.5 m.
    const auto closure = Closure(PoseFromXYZRPY(0, 0, 0, 0, 0, kPi), 12);
    PredictedClosureConfig config;
    config.max_distance = 0.5;
    const auto pairs = ExpandMapClosures({closure}, Odometry(), config);
    ASSERT_EQ(pairs.size(), 1u);
    EXPECT_EQ(pairs[0].pair, (ScanPair{0, 10}));
}

TEST(CountPairsWithinTau, OnlyPairsAPerfectMapClosureCanPredict) {
    // Reference: scans 0-2 and 10-12 as in Odometry(), but the query map laid 3 m beside the
    // reference map in the world. Ground truth (overlap-based) holds all nine pairs across the maps.
    Poses reference(13, Eigen::Isometry3d::Identity());
    for (int k = 0; k < 3; ++k) {
        reference[k] = PoseFromXYZRPY(k, 0, 0, 0, 0, 0);
        reference[10 + k] = PoseFromXYZRPY(k, 3, 0.5, 0, 0, 0);
    }
    std::vector<ScanPair> ground_truth;
    for (std::size_t r = 0; r < 3; ++r)
        for (std::size_t q = 10; q < 13; ++q) ground_truth.push_back({r, q});
    PredictedClosureConfig config;
    config.max_distance = 3.5;
    config.planar = true;  // sqrt((r - q)^2 + 9) < 3.5: |r - q| <= 1
    EXPECT_EQ(CountPairsWithinTau(ground_truth, reference, config), 7u);
    // A closure with the exact relative pose predicts exactly those: the count is the recall ceiling.
    const auto closure = Closure(PoseFromXYZRPY(0, -3, -0.5, 0, 0, 0), 10);
    EXPECT_EQ(ExpandMapClosures({closure}, reference, config).size(), 7u);
    config.planar = false;  // the 0.5 m height counts: sqrt(1 + 9 + 0.25) < 3.5 still, sqrt(4 + 9.25) not
    EXPECT_EQ(CountPairsWithinTau(ground_truth, reference, config), 7u);
    config.max_distance = 3.1;  // only |r - q| = 0 in 3D (3.04 m), in the plane 3 m < 3.1 too
    EXPECT_EQ(CountPairsWithinTau(ground_truth, reference, config), 3u);
    ground_truth.push_back({2, 13});
    EXPECT_THROW(CountPairsWithinTau(ground_truth, reference, config), ConfigError);
}

TEST(EvaluateMapClosures, RightMapAndPoseError) {
    const Poses gt = Odometry();  // use the same poses as ground truth
    const Eigen::Isometry3d T_gt_query_ref = gt[10].inverse() * gt[0];
    const Eigen::Isometry3d error = PoseFromXYZRPY(0.3, 0.4, 0.0, 0.0, 0.0, 2.0 * kPi / 180.0);
    std::vector<MapClosureForEval> closures = {Closure(T_gt_query_ref * error, 30), Closure(T_gt_query_ref, 4)};
    MapClosureForEval wrong = Closure(Eigen::Isometry3d::Identity(), 40);
    wrong.ref_first_scan = 3;  // scans 3-5 never overlap the query map
    wrong.ref_last_scan = 5;
    closures.push_back(wrong);
    const std::vector<ScanPair> gt_pairs = {{4, 8}, {11, 1}};  // (1, 11) given reversed
    const auto metrics = EvaluateMapClosures(closures, gt, gt_pairs, MapMetricsConfig{});
    ASSERT_EQ(metrics.closures.size(), 2u);  // the closure with 4 inliers is below gamma = 10
    EXPECT_TRUE(metrics.closures[0].right_map);
    EXPECT_EQ(metrics.closures[0].gt_scan_pairs, 1u);
    EXPECT_NEAR(metrics.closures[0].translation_error, 0.5, 1e-9);
    EXPECT_NEAR(metrics.closures[0].yaw_error_deg, 2.0, 1e-9);
    EXPECT_FALSE(metrics.closures[1].right_map);
    EXPECT_EQ(metrics.closures[1].closure, 2u);
    EXPECT_EQ(metrics.num_right_maps, 1u);
    EXPECT_DOUBLE_EQ(metrics.fraction_right, 0.5);
    EXPECT_EQ(metrics.translation_error.count, 1u);
    EXPECT_NEAR(metrics.yaw_error_deg.max, 2.0, 1e-9);
}

TEST(EvaluateMapClosures, CountsEachPairBetweenTheMapsOnceEitherWayRound) {
    // Ranges that overlap (scans 5-9 in both): a pair inside the overlap is counted once; a pair given
    // reversed, or twice, counts once; pairs with a scan outside both maps do not count.
    MapClosureForEval c = Closure(Eigen::Isometry3d::Identity(), 30);
    c.ref_first_scan = 0;
    c.ref_last_scan = 9;
    c.query_first_scan = 5;
    c.query_last_scan = 14;
    Poses gt(21, Eigen::Isometry3d::Identity());
    const std::vector<ScanPair> gt_pairs = {{2, 12}, {6, 8}, {12, 3}, {3, 12}, {7, 20}, {1, 4}, {14, 5}};
    const auto metrics = EvaluateMapClosures({c}, gt, gt_pairs, MapMetricsConfig{});
    ASSERT_EQ(metrics.closures.size(), 1u);
    EXPECT_EQ(metrics.closures[0].gt_scan_pairs, 4u);  // (2,12), (3,12), (6,8), (5,14); not (1,4), (7,20)
}

TEST(ComputeMapRecall, CountsMapsThatRevisitAndThoseFoundRight) {
    // Maps of 3 scans: 0-2, 3-5, 6-8, 9-11, 12-14. Map 3 truly revisits map 0, map 4 revisits map 1.
    const std::vector<MapRange> maps = {{0, 2}, {3, 5}, {6, 8}, {9, 11}, {12, 14}};
    const std::vector<ScanPair> gt_pairs = {{1, 10}, {2, 11}, {13, 4}};
    MapClosureForEval right;  // map 3 -> map 0: right
    right.query_first_scan = 9;
    right.query_last_scan = 11;
    right.ref_first_scan = 0;
    right.ref_last_scan = 2;
    right.inliers = 20;
    MapClosureForEval wrong = right;  // map 4 -> map 2: wrong
    wrong.query_first_scan = 12;
    wrong.query_last_scan = 14;
    wrong.ref_first_scan = 6;
    wrong.ref_last_scan = 8;
    MapClosureForEval weak = wrong;  // map 4 -> map 1 is right but below gamma
    weak.ref_first_scan = 3;
    weak.ref_last_scan = 5;
    weak.inliers = 5;
    const auto recall = ComputeMapRecall(maps, {right, wrong, weak}, gt_pairs, MapMetricsConfig{});
    EXPECT_EQ(recall.maps_with_revisit, 2u);
    EXPECT_EQ(recall.maps_found_right, 1u);
    EXPECT_DOUBLE_EQ(recall.recall, 0.5);
    MapMetricsConfig permissive;
    permissive.min_inliers = 5;
    EXPECT_DOUBLE_EQ(ComputeMapRecall(maps, {weak, wrong, right}, gt_pairs, permissive).recall, 1.0);
}

}  // namespace
}  // namespace revisit
