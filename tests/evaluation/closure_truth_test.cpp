#include <gtest/gtest.h>

#include <cmath>

#include "core/error.hpp"
#include "core/se3.hpp"
#include "evaluation/closure_truth.hpp"

namespace revisit {
namespace {

/// Out 30 m along x and back on a parallel lane 1 m to the side, one scan per metre: 61 scans.
Poses OutAndBack() {
    Poses poses;
    for (int k = 0; k <= 30; ++k) poses.push_back(PoseFromXYZRPY(k, 0.0, 0.0, 0.0, 0.0, 0.0));
    for (int k = 29; k >= 0; --k) poses.push_back(PoseFromXYZRPY(k, 1.0, 0.0, 0.0, 0.0, M_PI));
    return poses;
}

TEST(ClosureTruth, TrueWithinTheThresholdsFalseBeyond) {
    const Poses reference = OutAndBack();
    const Eigen::Isometry3d T_gt = reference[50].inverse() * reference[5];
    auto closure = [&](const Eigen::Isometry3d& error) {
        MapClosureForEval c;
        c.query_first_scan = 50;
        c.ref_first_scan = 5;
        c.T_query_ref = T_gt * error;
        return c;
    };
    const auto truth = JudgeClosures({closure(PoseFromXYZRPY(0.3, 0.2, 0, 0, 0, 0.01)),
                                      closure(PoseFromXYZRPY(0.6, 0.0, 0, 0, 0, 0.0)),
                                      closure(PoseFromXYZRPY(0.0, 0.0, 0, 0, 0, 3.0 * M_PI / 180.0))},
                                     reference, ClosureTruthConfig{});
    EXPECT_EQ(truth.num_true, 1u);
    EXPECT_EQ(truth.num_false, 2u);
    EXPECT_TRUE(truth.verdicts[0].is_true);
    EXPECT_NEAR(truth.verdicts[1].error.translation, 0.6, 1e-9);
    EXPECT_NEAR(truth.verdicts[2].error.yaw_deg, 3.0, 1e-9);
}

/// A straight street driven twice, one scan per metre: scans 0..99 (the reference map) and 100..199 (the
/// query map), the second pass starting 60 m further along, so the maps overlap over their last and first
/// 40 m. `scale`: the odometry's error of travelled distance (1.02: 2% too far).
Poses StraightStreet(double scale) {
    Poses poses;
    for (int k = 0; k < 100; ++k) poses.push_back(PoseFromXYZRPY(scale * k, 0.0, 0.0, 0.0, 0.0, 0.0));
    for (int k = 0; k < 100; ++k) poses.push_back(PoseFromXYZRPY(scale * (60.0 + k), 3.0, 0.0, 0.0, 0.0, 0.0));
    return poses;
}

TEST(ClosureTruth, JudgesAClosureWhereItsMapsOverlapNotAtTheirOrigins) {
    const Poses reference = StraightStreet(1.0);
    // The odometry drives each map 2% too far: within a map, the scans overlap the other map 1.2-2 m
    // from where they are. A registration aligns the overlap (ref scan 80 on query scan 120, the
    // middle of the overlap): right there, 1.2 m off at the first scans.
    const Poses odometry = StraightStreet(1.02);
    MapClosureForEval c;
    c.query_first_scan = 100;
    c.query_last_scan = 199;
    c.ref_first_scan = 0;
    c.ref_last_scan = 99;
    const Eigen::Isometry3d T_query_120 = odometry[100].inverse() * odometry[120];
    const Eigen::Isometry3d T_ref_80 = odometry[0].inverse() * odometry[80];
    c.T_query_ref = T_query_120 * (reference[120].inverse() * reference[80]) * T_ref_80.inverse();

    const auto at_first_scans = JudgeClosures({c}, reference, ClosureTruthConfig{});
    EXPECT_EQ(at_first_scans.num_false, 1u);
    EXPECT_NEAR(at_first_scans.verdicts[0].error.translation, 1.2, 1e-6);

    const auto anchored = JudgeClosures({c}, reference, ClosureTruthConfig{}, odometry);
    ASSERT_EQ(anchored.num_true, 1u);
    const ClosureVerdict& v = anchored.verdicts[0];
    // The anchor is found from the odometry and the closure alone: the first pair of scans (one of each
    // map) that the closure lays on each other, here where the maps overlap.
    EXPECT_GE(v.ref_scan, 60u);
    EXPECT_LE(v.query_scan, 139u);
    EXPECT_LT(v.error.translation, 0.5);
    EXPECT_NEAR(v.first_scan_error.translation, 1.2, 1e-6);

    // A closure 1 m off where the maps overlap stays false wherever it is judged.
    MapClosureForEval off = c;
    off.T_query_ref = PoseFromXYZRPY(1.0, 0.0, 0.0, 0.0, 0.0, 0.0) * c.T_query_ref;
    const auto wrong = JudgeClosures({off}, reference, ClosureTruthConfig{}, odometry);
    EXPECT_EQ(wrong.num_false, 1u);
    EXPECT_NEAR(wrong.verdicts[0].error.translation, 1.0, 0.05);
}

TEST(ClosureTruth, AnchorIsThePairOfScansTheClosureLaysNearestEachOther) {
    const Poses poses = StraightStreet(1.0);
    MapClosureForEval c;
    c.query_first_scan = 100;
    c.query_last_scan = 199;
    c.ref_first_scan = 0;
    c.ref_last_scan = 99;
    c.T_query_ref = poses[100].inverse() * poses[0];
    const ClosureAnchor anchor = AnchorOf(c, poses);
    // Query scan 100 (x = 60, y = 3) lies 3 m beside reference scan 60, the nearest pair; the first in scan order.
    EXPECT_EQ(anchor.query_scan, 100u);
    EXPECT_EQ(anchor.ref_scan, 60u);
    EXPECT_TRUE(anchor.T_query_scan_ref_scan.isApprox(poses[100].inverse() * poses[60], 1e-9));
    c.ref_last_scan = 200;
    EXPECT_THROW(AnchorOf(c, poses), ConfigError);
}

TEST(RevisitCoverage, CountsRevisitingScansInMapsJoinedByATrueClosure) {
    const Poses reference = OutAndBack();
    ClosureTruthConfig config;  // 3 m, 20 m
    const auto revisits = FindRevisits(reference, config.revisit_radius, config.revisit_gap);
    // Brute force: scan i revisits e when 20 m of travel lie between them and they are within 3 m.
    std::vector<double> travel(reference.size(), 0.0);
    for (std::size_t i = 1; i < reference.size(); ++i)
        travel[i] = travel[i - 1] + (reference[i].translation() - reference[i - 1].translation()).norm();
    std::size_t expected = 0;
    for (std::size_t i = 0; i < reference.size(); ++i) {
        std::vector<std::size_t> earlier;
        for (std::size_t e = 0; e < i; ++e) {
            if (travel[i] - travel[e] >= 20.0 &&
                (reference[i].translation() - reference[e].translation()).norm() <= 3.0)
                earlier.push_back(e);
        }
        EXPECT_EQ(revisits[i], earlier) << "scan " << i;
        expected += earlier.empty() ? 0 : 1;
    }
    EXPECT_EQ(expected, 22u);  // the return at x = 0..21 m

    // Maps of 10 scans (the last holds scan 60 alone).
    std::vector<MapRange> maps;
    for (std::size_t first = 0; first < reference.size(); first += 10) maps.push_back({first, std::min(first + 9, reference.size() - 1)});
    const auto none = ComputeRevisitCoverage(revisits, maps, {});
    EXPECT_EQ(none.revisit_scans, expected);
    EXPECT_EQ(none.covered_scans, 0u);
    const auto some = ComputeRevisitCoverage(revisits, maps, {{0, 5}});  // map 5 = scans 50..59, back at x 9..0
    EXPECT_EQ(some.covered_scans, 10u);
    EXPECT_NEAR(some.coverage, 10.0 / double(expected), 1e-12);
    // Either direction: the pair given as (reference, query) counts the same.
    EXPECT_EQ(ComputeRevisitCoverage(revisits, maps, {{5, 0}}).covered_scans, 10u);
}

}  // namespace
}  // namespace revisit
