#include <gtest/gtest.h>

#include <cmath>

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
