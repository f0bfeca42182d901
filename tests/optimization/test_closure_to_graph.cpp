#include <gtest/gtest.h>

#include <cmath>

#include "core/se3.hpp"
#include "optimization/cloud_fixtures.hpp"
#include "optimization/pose_graph.hpp"
#include "optimization/refinement.hpp"

namespace revisit {
namespace {

// The conventions between the stages, end to end: a refined closure (query map = `from`,
// reference map = `to`, T_from_to = T_query_ref, information from the registration) closes a
// drifted loop so that the query node lands where the scene says it is.
TEST(ClosureToGraph, RefinedClosureWithItsInformationClosesADriftedLoop) {
    const auto street_in_world = testing::SyntheticStreet(100.0, 10.0, 7);
    // A square loop of 4 x 10 nodes, 10 m apart, that ends back near the first node.
    Poses truth;
    for (int side = 0; side < 4; ++side)
        for (int k = 0; k < 10; ++k) {
            const double yaw = side * M_PI / 2.0;
            const Eigen::Vector3d corner = side == 0 ? Eigen::Vector3d(0, 0, 0)
                                         : side == 1 ? Eigen::Vector3d(100, 0, 0)
                                         : side == 2 ? Eigen::Vector3d(100, 100, 0)
                                                     : Eigen::Vector3d(0, 100, 0);
            const Eigen::Vector3d along(std::cos(yaw), std::sin(yaw), 0.0);
            truth.push_back(PoseFromXYZRPY(0, 0, 0, 0, 0, yaw));
            truth.back().translation() = corner + 10.0 * k * along;
        }
    // The last node sits 3 m from the first, turned by 25 degrees.
    truth.push_back(PoseFromXYZRPY(3.0, -1.0, 0.0, 0.0, 0.0, 2.0 * M_PI + 25.0 * M_PI / 180.0));
    const int query = static_cast<int>(truth.size()) - 1;

    // Odometry whose heading drifts by 0.11 degrees per step.
    Poses odometry = {truth.front()};
    for (std::size_t i = 1; i < truth.size(); ++i)
        odometry.push_back(odometry.back() * truth[i - 1].inverse() * truth[i] * PoseFromXYZRPY(0.02, 0, 0, 0, 0, 0.002));
    ASSERT_GT((odometry[query].translation() - truth[query].translation()).norm(), 5.0);

    // Both local maps see the same street; the 2D guess comes from the drifted odometry.
    const Eigen::Isometry3d T_query_ref_true = truth[query].inverse() * truth[0];
    const auto ref_points = testing::Transform(truth[0].inverse(), testing::Subsample(street_in_world, 2, 0));
    const auto query_points = testing::Transform(truth[query].inverse(), testing::Subsample(street_in_world, 2, 1));
    const Eigen::Isometry3d guess = T_query_ref_true * PoseFromXYZRPY(0.6, -0.4, 0.0, 0.0, 0.0, 0.04);
    const auto refined = RefineAlignment(ref_points, query_points, guess, RefinementConfig{});
    ASSERT_TRUE(refined.accepted) << refined.reason;

    auto edges = OdometryEdges(odometry, DiagonalInformation(0.1, 0.003));
    edges.push_back({query, 0, refined.T_query_ref, refined.information, true});
    const auto result = OptimizePoseGraph(odometry, edges, PoseGraphConfig{});
    const Eigen::Isometry3d T_query_ref_optimized = result.T_world_node[query].inverse() * result.T_world_node[0];
    const Eigen::Isometry3d error = T_query_ref_true.inverse() * T_query_ref_optimized;
    EXPECT_LT(error.translation().norm(), 0.05);
    EXPECT_LT(RotationAngle(error), 0.1 * M_PI / 180.0);
    EXPECT_GT(result.edge_weights.back(), 0.5);
}

}  // namespace
}  // namespace revisit
