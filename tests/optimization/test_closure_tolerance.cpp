// A closure's tolerance band in the pose graph (PoseGraphConfig::loop_tolerance_chi2): odometry that
// already agrees with a closure within the closure's own uncertainty is not pulled off by it.
#include <gtest/gtest.h>

#include <cmath>

#include "core/se3.hpp"
#include "optimization/drift_simulation.hpp"
#include "optimization/pose_graph.hpp"
#include "optimization/robust_loss.hpp"

namespace revisit {
namespace {

constexpr double kTolerance = 12.59;  // chi^2(6 dof), 95% quantile

/// 40 nodes 10 m apart around a 100 x 100 m block (a left turn at each corner), the last one 10 m
/// short of the first.
Poses Block() {
    Poses route = {Eigen::Isometry3d::Identity()};
    for (int node = 1; node < 40; ++node)
        route.push_back(route.back() * PoseFromXYZRPY(10.0, 0.0, 0.0, 0.0, 0.0, node % 10 == 0 ? M_PI / 2.0 : 0.0));
    return route;
}

/// The odometry edges of `odometry` and one closure from the last node to the first.
std::vector<PoseGraphEdge> GraphWithClosure(const Poses& odometry, const Eigen::Isometry3d& T_last_first, const Matrix6d& information) {
    auto edges = OdometryEdges(odometry, OdometryInformation(10.0));
    edges.push_back({static_cast<int>(odometry.size()) - 1, 0, T_last_first, information, true});
    return edges;
}

double LargestMove(const Poses& a, const Poses& b) {
    double largest = 0.0;
    for (std::size_t i = 0; i < a.size(); ++i) largest = std::max(largest, (a[i].translation() - b[i].translation()).norm());
    return largest;
}

TEST(ClosureTolerance, AClosureTheOdometryAgreesWithDoesNotMoveTheGraph) {
    const Poses odometry = Block();  // drift-free odometry
    // The closure's registration is 3 cm and 0.1 deg off the truth, within its own uncertainty.
    const Matrix6d information = DiagonalInformation(0.03, 0.003);
    const Eigen::Isometry3d T_last_first =
        odometry.back().inverse() * odometry.front() * PoseFromXYZRPY(0.03, 0.0, 0.0, 0.0, 0.0, 0.1 * M_PI / 180.0);
    const auto edges = GraphWithClosure(odometry, T_last_first, information);
    ASSERT_LT(EdgeChi2(edges.back(), odometry.back(), odometry.front()), kTolerance);

    PoseGraphConfig config;
    config.loop_tolerance_chi2 = kTolerance;
    const auto kept = OptimizePoseGraph(odometry, edges, config);
    EXPECT_LT(LargestMove(kept.T_world_node, odometry), 1e-9);
    EXPECT_DOUBLE_EQ(kept.edge_weights.back(), 1.0);  // it agrees: not down-weighted, only not pulling

    // Without the band the same closure bends the drift-free odometry by its own error.
    const auto pulled = OptimizePoseGraph(odometry, edges, PoseGraphConfig{});
    EXPECT_GT(LargestMove(pulled.T_world_node, odometry), 0.02);
}

TEST(ClosureTolerance, AClosureBeyondItsToleranceStillCorrectsTheDrift) {
    const Poses truth = Block();
    Poses odometry = {truth.front()};  // 0.2 deg of heading error per 10 m step
    for (std::size_t i = 1; i < truth.size(); ++i)
        odometry.push_back(odometry.back() * truth[i - 1].inverse() * truth[i] * PoseFromXYZRPY(0.0, 0.0, 0.0, 0.0, 0.0, 0.2 * M_PI / 180.0));
    const Matrix6d information = DiagonalInformation(0.03, 0.003);
    const auto edges = GraphWithClosure(odometry, truth.back().inverse() * truth.front(), information);
    const double gap_before = (odometry.back().translation() - truth.back().translation()).norm();
    ASSERT_GT(gap_before, 5.0);

    PoseGraphConfig config;
    config.anneal = true;  // as the pipeline runs it: a lone closure 40 m from the drifted odometry
    config.loop_tolerance_chi2 = kTolerance;
    const auto result = OptimizePoseGraph(odometry, edges, config);
    const double gap_after = (result.T_world_node.back().translation() - truth.back().translation()).norm();
    // The drift goes, up to the band: the closure ends within its onset zone (chi^2 < 2 tau: 0.15 m at
    // its 0.03 m sigma), and nothing turned it down.
    EXPECT_LT(gap_after, 0.15);
    EXPECT_LT(result.edge_chi2.back(), 2.0 * kTolerance);
    EXPECT_GT(result.edge_weights.back(), 0.5);
}

TEST(ToleranceLoss, IsZeroInTheBandAndMatchesItsDerivatives) {
    for (const auto kind : {RobustLossKind::kNone, RobustLossKind::kCauchy}) {
        const auto loss = MakeLoopLoss(kind, 10.0, kTolerance);
        for (const double chi2 : {0.0, 5.0, kTolerance, 15.0, 20.0, 30.0, 1e3}) {
            double rho[3], plus[3], minus[3];
            const double h = 1e-5;
            loss->Evaluate(chi2, rho);
            loss->Evaluate(chi2 + h, plus);
            loss->Evaluate(std::max(0.0, chi2 - h), minus);
            if (chi2 <= kTolerance) {
                EXPECT_EQ(rho[0], 0.0);
                EXPECT_EQ(rho[1], 0.0);
                continue;
            }
            EXPECT_NEAR(rho[1], (plus[0] - minus[0]) / (2.0 * h), 1e-6) << chi2;
            EXPECT_NEAR(rho[2], (plus[1] - minus[1]) / (2.0 * h), 1e-5) << chi2;
            EXPECT_GT(rho[1], 0.0);
        }
    }
    // The kernel's weight is taken at the excess: 1 within the band, the kernel's beyond it.
    EXPECT_DOUBLE_EQ(LoopWeight(RobustLossKind::kCauchy, 10.0, kTolerance, 5.0), 1.0);
    EXPECT_NEAR(LoopWeight(RobustLossKind::kCauchy, 10.0, kTolerance, 100.0), RobustWeight(RobustLossKind::kCauchy, 10.0, 100.0 - 1.5 * kTolerance), 1e-12);
    EXPECT_DOUBLE_EQ(LoopWeight(RobustLossKind::kCauchy, 10.0, 0.0, 100.0), RobustWeight(RobustLossKind::kCauchy, 10.0, 100.0));
    EXPECT_EQ(MakeLoopLoss(RobustLossKind::kNone, 10.0, 0.0), nullptr);
}

}  // namespace
}  // namespace revisit
