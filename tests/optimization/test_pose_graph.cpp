#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <numeric>
#include <stdexcept>

#include "core/se3.hpp"
#include "optimization/drift_simulation.hpp"
#include "optimization/pose_graph.hpp"

namespace revisit {
namespace {

/// A drifted city route with its true closures, the graph the pipeline would build.
struct Scenario {
    Poses truth;
    Poses odometry;
    std::vector<PoseGraphEdge> edges;  ///< odometry first, then closures
    std::size_t num_odometry_edges = 0;
};

Scenario MakeCityScenario(const Matrix6d& odometry_information, const Matrix6d& closure_information) {
    Scenario scenario;
    scenario.truth = testing::CityRoute(10.0);
    scenario.odometry = testing::DriftingOdometry(scenario.truth, testing::DriftModel{});
    scenario.edges = OdometryEdges(scenario.odometry, odometry_information);
    scenario.num_odometry_edges = scenario.edges.size();
    const auto closures = testing::TrueClosures(scenario.truth, 8.0, 200.0, 3, closure_information, 17);
    scenario.edges.insert(scenario.edges.end(), closures.begin(), closures.end());
    return scenario;
}

// Information consistent with the drift model: 10 m steps, ~0.1 m and ~0.003 rad per step.
const Matrix6d kOdometryInformation = OdometryInformation(10.0);
const Matrix6d kClosureInformation = DiagonalInformation(0.1, 0.005);

TEST(OptimizePoseGraph, CorrectsDriftOfSyntheticCityRoute) {
    const auto scenario = MakeCityScenario(kOdometryInformation, kClosureInformation);
    ASSERT_GT(PathLength(scenario.truth), 4000.0);
    ASSERT_GT(scenario.edges.size() - scenario.num_odometry_edges, 30u);
    const auto result = OptimizePoseGraph(scenario.odometry, scenario.edges, PoseGraphConfig{});
    const double before = testing::ApeTranslationRmse(scenario.odometry, scenario.truth);
    const double after = testing::ApeTranslationRmse(result.T_world_node, scenario.truth);
    std::cout << "[ city ] nodes " << scenario.truth.size() << " closures " << scenario.edges.size() - scenario.num_odometry_edges
              << " APE before " << before << " m after " << after << " m, stages " << result.stages << "\n";
    EXPECT_GT(before, 40.0);
    EXPECT_LT(after, 0.2 * before);  // the 80% reduction; measured ~95%
    EXPECT_LT(after, 4.0);
    EXPECT_EQ(result.anchored_nodes, 1);
    EXPECT_TRUE(result.T_world_node.front().isApprox(scenario.odometry.front()));
    for (std::size_t k = scenario.num_odometry_edges; k < scenario.edges.size(); ++k) EXPECT_GT(result.edge_weights[k], 0.5) << k;
}

TEST(OptimizePoseGraph, WrongClosuresEndWithLowWeightAndDoNotBendTheMap) {
    auto scenario = MakeCityScenario(kOdometryInformation, kClosureInformation);
    const std::size_t num_true = scenario.edges.size() - scenario.num_odometry_edges;
    const auto clean = OptimizePoseGraph(scenario.odometry, scenario.edges, PoseGraphConfig{});
    // 10% wrong closures of plausible size between places at least 50 m apart.
    const int num_false = static_cast<int>((num_true + 8) / 9);
    const auto wrong = testing::FalseClosures(scenario.truth, num_false, 50.0, kClosureInformation, 23);
    scenario.edges.insert(scenario.edges.end(), wrong.begin(), wrong.end());
    const auto result = OptimizePoseGraph(scenario.odometry, scenario.edges, PoseGraphConfig{});
    const double clean_ape = testing::ApeTranslationRmse(clean.T_world_node, scenario.truth);
    const double ape = testing::ApeTranslationRmse(result.T_world_node, scenario.truth);
    double max_wrong_weight = 0.0;
    for (std::size_t k = scenario.edges.size() - wrong.size(); k < scenario.edges.size(); ++k)
        max_wrong_weight = std::max(max_wrong_weight, result.edge_weights[k]);
    double mean_true_weight = 0.0;
    for (std::size_t k = scenario.num_odometry_edges; k < scenario.num_odometry_edges + num_true; ++k)
        mean_true_weight += result.edge_weights[k] / static_cast<double>(num_true);
    std::cout << "[ wrong closures ] " << num_false << " wrong of " << num_true + wrong.size() << ": APE clean " << clean_ape
              << " m, with wrong " << ape << " m, max wrong weight " << max_wrong_weight << ", mean true weight "
              << mean_true_weight << "\n";
    EXPECT_LT(ape, 1.2 * clean_ape);
    EXPECT_LT(max_wrong_weight, 0.01);
    EXPECT_GT(mean_true_weight, 0.8);
}

TEST(OptimizePoseGraph, LeastSquaresIsBentByWrongClosures) {
    // The control experiment: the same wrong closures without a robust loss ruin the map,
    // so the previous test's result is the loss' doing.
    auto scenario = MakeCityScenario(kOdometryInformation, kClosureInformation);
    const auto wrong = testing::FalseClosures(scenario.truth, 7, 50.0, kClosureInformation, 23);
    scenario.edges.insert(scenario.edges.end(), wrong.begin(), wrong.end());
    PoseGraphConfig config;
    config.loop_loss = RobustLossKind::kNone;
    const auto result = OptimizePoseGraph(scenario.odometry, scenario.edges, config);
    EXPECT_GT(testing::ApeTranslationRmse(result.T_world_node, scenario.truth), 10.0);
    for (const double weight : result.edge_weights) EXPECT_EQ(weight, 1.0);
}

TEST(OptimizePoseGraph, DynamicCovarianceScalingWithAnnealingAlsoRejectsWrongClosures) {
    auto scenario = MakeCityScenario(kOdometryInformation, kClosureInformation);
    const auto wrong = testing::FalseClosures(scenario.truth, 7, 50.0, kClosureInformation, 29);
    scenario.edges.insert(scenario.edges.end(), wrong.begin(), wrong.end());
    PoseGraphConfig config;
    config.loop_loss = RobustLossKind::kDynamicCovarianceScaling;
    config.anneal = true;
    const auto result = OptimizePoseGraph(scenario.odometry, scenario.edges, config);
    EXPECT_GT(result.stages, 1);
    EXPECT_LT(testing::ApeTranslationRmse(result.T_world_node, scenario.truth), 4.0);
    for (std::size_t k = scenario.edges.size() - wrong.size(); k < scenario.edges.size(); ++k)
        EXPECT_LT(result.edge_weights[k], 0.01);
}

TEST(OptimizePoseGraph, SingleWrongClosureIsDownWeighted) {
    // Only odometry and one wrong closure: nothing supports it, the odometry chain opposes it.
    auto scenario = MakeCityScenario(kOdometryInformation, kClosureInformation);
    scenario.edges.resize(scenario.num_odometry_edges);
    const auto wrong = testing::FalseClosures(scenario.truth, 1, 80.0, kClosureInformation, 3);
    scenario.edges.push_back(wrong.front());
    const auto result = OptimizePoseGraph(scenario.odometry, scenario.edges, PoseGraphConfig{});
    EXPECT_LT(result.edge_weights.back(), 0.01);
    // The map barely moves: the odometry is kept within a few metres.
    EXPECT_LT(testing::ApeTranslationRmse(result.T_world_node, scenario.odometry), 3.0);
}

TEST(OptimizePoseGraph, WithoutClosuresKeepsTheOdometry) {
    const auto scenario = MakeCityScenario(kOdometryInformation, kClosureInformation);
    const std::vector<PoseGraphEdge> odometry_only(scenario.edges.begin(), scenario.edges.begin() + scenario.num_odometry_edges);
    const auto result = OptimizePoseGraph(scenario.odometry, odometry_only, PoseGraphConfig{});
    ASSERT_EQ(result.T_world_node.size(), scenario.odometry.size());
    for (std::size_t i = 0; i < scenario.odometry.size(); ++i)
        EXPECT_LT((result.T_world_node[i].translation() - scenario.odometry[i].translation()).norm(), 1e-6) << i;
    EXPECT_NEAR(result.final_cost, 0.0, 1e-9);
}

TEST(OptimizePoseGraph, SingleNodeAndEmptyGraphAreReturnedUnchanged) {
    const Poses one = {PoseFromXYZRPY(1.0, 2.0, 3.0, 0.1, 0.2, 0.3)};
    const auto result = OptimizePoseGraph(one, {}, PoseGraphConfig{});
    ASSERT_EQ(result.T_world_node.size(), 1u);
    EXPECT_TRUE(result.T_world_node[0].isApprox(one[0]));
    EXPECT_TRUE(OptimizePoseGraph({}, {}, PoseGraphConfig{}).T_world_node.empty());
}

TEST(OptimizePoseGraph, DisconnectedPiecesAreEachAnchoredAtTheirFirstNode) {
    // Nodes 0-2 and 3-5 form two chains with no edge between them, node 6 has no edge at all.
    Poses truth;
    for (int i = 0; i < 7; ++i) truth.push_back(PoseFromXYZRPY(10.0 * i, 0.0, 0.0, 0.0, 0.0, 0.1 * i));
    Poses start = truth;
    for (int i = 1; i < 7; ++i) start[i].translation() += Eigen::Vector3d(0.5 * i, -0.3 * i, 0.2);  // perturbed
    std::vector<PoseGraphEdge> edges;
    for (int i : {0, 1, 3, 4}) edges.push_back({i, i + 1, truth[i].inverse() * truth[i + 1], Matrix6d::Identity(), false});
    edges.push_back({2, 0, truth[2].inverse() * truth[0], Matrix6d::Identity() * 100.0, true});
    const auto result = OptimizePoseGraph(start, edges, PoseGraphConfig{});
    EXPECT_EQ(result.anchored_nodes, 2);
    EXPECT_TRUE(result.T_world_node[0].isApprox(start[0]));
    EXPECT_TRUE(result.T_world_node[3].isApprox(start[3]));
    EXPECT_TRUE(result.T_world_node[6].isApprox(start[6]));
    // Each piece now agrees with its measurements, relative to its own anchor.
    for (int i : {1, 2}) EXPECT_LT(((start[0].inverse() * result.T_world_node[i]).translation() - (truth[0].inverse() * truth[i]).translation()).norm(), 1e-4);
    for (int i : {4, 5}) EXPECT_LT(((start[3].inverse() * result.T_world_node[i]).translation() - (truth[3].inverse() * truth[i]).translation()).norm(), 1e-4);
}

TEST(OptimizePoseGraph, PlanarGraphStaysPlanar) {
    // 2D laser data (radish): poses and measurements in the plane must stay in the plane.
    auto scenario = MakeCityScenario(kOdometryInformation, kClosureInformation);
    auto flatten = [](const Eigen::Isometry3d& T) {
        const double yaw = std::atan2(T.linear()(1, 0), T.linear()(0, 0));
        return PoseFromXYZRPY(T.translation().x(), T.translation().y(), 0.0, 0.0, 0.0, yaw);
    };
    for (auto& T : scenario.truth) T = flatten(T);
    for (auto& T : scenario.odometry) T = flatten(T);
    for (auto& edge : scenario.edges) edge.T_from_to = flatten(edge.T_from_to);
    const auto result = OptimizePoseGraph(scenario.odometry, scenario.edges, PoseGraphConfig{});
    for (const auto& T : result.T_world_node) {
        EXPECT_NEAR(T.translation().z(), 0.0, 1e-6);
        EXPECT_NEAR(T.linear()(2, 2), 1.0, 1e-9);
    }
    EXPECT_LT(testing::ApeTranslationRmse(result.T_world_node, scenario.truth), 0.2 * testing::ApeTranslationRmse(scenario.odometry, scenario.truth));
}

TEST(OptimizePoseGraph, RejectsEdgesToMissingNodes) {
    const Poses two(2, Eigen::Isometry3d::Identity());
    EXPECT_THROW(OptimizePoseGraph(two, {{0, 2, Eigen::Isometry3d::Identity(), Matrix6d::Identity(), true}}, {}), std::out_of_range);
    EXPECT_THROW(OptimizePoseGraph(two, {{1, 1, Eigen::Isometry3d::Identity(), Matrix6d::Identity(), true}}, {}), std::out_of_range);
}

TEST(OptimizePoseGraph, AcceptsRankDeficientInformation) {
    // A registration in a corridor constrains 5 of 6 directions: information of rank 5.
    const Poses start = {Eigen::Isometry3d::Identity(), PoseFromXYZRPY(1.0, 0.0, 0.0, 0.0, 0.0, 0.0)};
    Matrix6d information = Matrix6d::Identity();
    information(0, 0) = 0.0;
    const PoseGraphEdge edge{0, 1, PoseFromXYZRPY(1.0, 0.5, 0.0, 0.0, 0.0, 0.0), information, false};
    const auto result = OptimizePoseGraph(start, {edge}, PoseGraphConfig{});
    EXPECT_NEAR(result.T_world_node[1].translation().y(), 0.5, 1e-6);
    EXPECT_TRUE(std::isfinite(result.T_world_node[1].translation().x()));
}

TEST(OptimizePoseGraph, ReportsTheTimeLimit) {
    auto scenario = MakeCityScenario(kOdometryInformation, kClosureInformation);
    PoseGraphConfig config;
    config.max_time_s = 1e-9;
    const auto result = OptimizePoseGraph(scenario.odometry, scenario.edges, config);
    EXPECT_TRUE(result.hit_time_limit);
    ASSERT_EQ(result.T_world_node.size(), scenario.odometry.size());
    for (const auto& T : result.T_world_node) EXPECT_TRUE(T.matrix().allFinite());
}

TEST(EdgeChi2, IsZeroForAPerfectMeasurementAndGrowsWithError) {
    const auto a = PoseFromXYZRPY(1.0, 2.0, 0.5, 0.1, -0.2, 0.7);
    const auto b = PoseFromXYZRPY(-3.0, 4.0, 1.0, 0.0, 0.3, -2.0);
    PoseGraphEdge edge{0, 1, a.inverse() * b, DiagonalInformation(0.1, 0.01), true};
    EXPECT_NEAR(EdgeChi2(edge, a, b), 0.0, 1e-12);
    Eigen::Isometry3d moved = b;
    moved.translation() += a.linear() * Eigen::Vector3d(0.1, 0.0, 0.0);  // 0.1 m = one sigma
    EXPECT_NEAR(EdgeChi2(edge, a, moved), 1.0, 1e-9);
}

TEST(InvertEdge, KeepsChi2AndTheOptimum) {
    const auto a = PoseFromXYZRPY(1.0, 2.0, 0.5, 0.1, -0.2, 0.7);
    const auto b = PoseFromXYZRPY(-8.0, 4.0, 1.0, 0.0, 0.3, -2.0);
    Matrix6d information = DiagonalInformation(0.05, 0.002);
    information(0, 4) = information(4, 0) = 300.0;  // a registration's correlated information
    const PoseGraphEdge edge{0, 1, a.inverse() * b, information, true};
    const auto inverted = InvertEdge(edge);
    EXPECT_EQ(inverted.from, 1);
    EXPECT_EQ(inverted.to, 0);
    EXPECT_TRUE(inverted.T_from_to.isApprox(b.inverse() * a));
    // A small error of the `to` node costs the same seen from either end.
    const Eigen::Isometry3d b_moved = b * PoseFromXYZRPY(0.02, -0.03, 0.01, 0.001, 0.002, -0.001);
    const double chi2 = EdgeChi2(edge, a, b_moved);
    EXPECT_GT(chi2, 1.0);
    EXPECT_NEAR(EdgeChi2(inverted, b_moved, a), chi2, 1e-3 * chi2);
    EXPECT_TRUE(InvertEdge(inverted).information.isApprox(information, 1e-9));
}

TEST(OdometryInformation, GrowsUncertaintyWithTravel) {
    EXPECT_TRUE(OdometryInformation(10.0).isApprox(DiagonalInformation(0.1, 0.003)));
    EXPECT_TRUE(OdometryInformation(0.5).isApprox(DiagonalInformation(0.02, 0.002)));  // floors
    EXPECT_LT(OdometryInformation(50.0)(0, 0), OdometryInformation(10.0)(0, 0));
}

TEST(RobustWeight, MatchesTheLossDerivative) {
    for (const auto kind : {RobustLossKind::kCauchy, RobustLossKind::kDynamicCovarianceScaling}) {
        const auto loss = MakeRobustLoss(kind, 10.0);
        for (const double chi2 : {0.5, 9.0, 50.0, 1e4}) {
            double rho[3];
            loss->Evaluate(chi2, rho);
            EXPECT_NEAR(rho[1], RobustWeight(kind, 10.0, chi2), 1e-12);
        }
    }
    EXPECT_EQ(MakeRobustLoss(RobustLossKind::kNone, 1.0), nullptr);
    EXPECT_DOUBLE_EQ(RobustWeight(RobustLossKind::kDynamicCovarianceScaling, 10.0, 5.0), 1.0);
}

}  // namespace
}  // namespace revisit
