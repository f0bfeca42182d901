#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <filesystem>
#include <iostream>
#include <random>
#include <set>
#include <stdexcept>

#include "core/se3.hpp"
#include "core/error.hpp"
#include "optimization/drift_simulation.hpp"
#include "optimization/global_map.hpp"
#include "optimization/online_pose_graph.hpp"
#include "optimization/point_grid.hpp"
#include "optimization/trajectory_correction.hpp"

namespace revisit {
namespace {

const Matrix6d kOdometryInformation = DiagonalInformation(0.1, 0.003);
const Matrix6d kClosureInformation = DiagonalInformation(0.1, 0.005);

/// Feeds the graph as a robot would: a node per step, each closure as soon as its query node
/// exists, a bounded update after each closure, the final batch at the end.
struct OnlineRun {
    OnlinePoseGraph graph;
    int updates = 0;
    int max_update_iterations = 0;
};

OnlineRun RunOnline(const Poses& odometry, std::vector<PoseGraphEdge> closures, const OnlinePoseGraphConfig& config) {
    std::sort(closures.begin(), closures.end(), [](const auto& a, const auto& b) { return std::max(a.from, a.to) < std::max(b.from, b.to); });
    OnlineRun run{OnlinePoseGraph(config)};
    std::size_t next = 0;
    for (std::size_t i = 0; i < odometry.size(); ++i) {
        run.graph.AddNode(odometry[i], kOdometryInformation);
        bool added = false;
        while (next < closures.size() && std::max(closures[next].from, closures[next].to) <= static_cast<int>(i)) {
            const auto& c = closures[next++];
            run.graph.AddLoop(c.from, c.to, c.T_from_to, c.information);
            added = true;
        }
        if (added) {
            run.max_update_iterations = std::max(run.max_update_iterations, run.graph.Update().iterations);
            ++run.updates;
        }
    }
    run.graph.Finish();
    return run;
}

/// Final weights of the wrong closures (measured pose 5 m or more off the truth) and the right ones.
struct ClosureWeights {
    double max_wrong = 0.0;
    std::size_t num_wrong = 0;
    double min_right = 1.0;
};

ClosureWeights SplitClosureWeights(const OnlinePoseGraph& graph, const Poses& truth) {
    ClosureWeights weights;
    for (std::size_t k = 0; k < graph.Edges().size(); ++k) {
        const auto& edge = graph.Edges()[k];
        if (!edge.is_loop) continue;
        const double weight = graph.LastResult().edge_weights[k];
        const Eigen::Isometry3d T_true = truth[edge.from].inverse() * truth[edge.to];
        if ((edge.T_from_to.inverse() * T_true).translation().norm() < 5.0) {
            weights.min_right = std::min(weights.min_right, weight);
        } else {
            weights.max_wrong = std::max(weights.max_wrong, weight);
            ++weights.num_wrong;
        }
    }
    return weights;
}

TEST(OnlinePoseGraph, IncrementalUpdatesThenFinalBatchCorrectTheDrift) {
    const auto truth = testing::CityRoute(10.0);
    const auto odometry = testing::DriftingOdometry(truth, testing::DriftModel{});
    auto closures = testing::TrueClosures(truth, 8.0, 200.0, 3, kClosureInformation, 17);
    const auto wrong = testing::FalseClosures(truth, 7, 50.0, kClosureInformation, 23);
    closures.insert(closures.end(), wrong.begin(), wrong.end());
    OnlinePoseGraphConfig config;
    const auto run = RunOnline(odometry, closures, config);
    ASSERT_EQ(run.graph.size(), truth.size());
    EXPECT_GT(run.updates, 20);
    EXPECT_LE(run.max_update_iterations, config.update_max_iterations);
    const double before = testing::ApeTranslationRmse(odometry, truth);
    const double after = testing::ApeTranslationRmse(run.graph.Estimates(), truth);
    std::cout << "[ online ] " << run.updates << " updates, APE before " << before << " m after " << after << " m\n";
    EXPECT_LT(after, 0.2 * before);
    EXPECT_LT(after, 4.0);
    const auto weights = SplitClosureWeights(run.graph, truth);
    ASSERT_EQ(weights.num_wrong, wrong.size());
    EXPECT_LT(weights.max_wrong, 0.01);
    EXPECT_GT(weights.min_right, 0.5);
}

TEST(OnlinePoseGraph, NewNodesContinueFromTheCorrectedPose) {
    OnlinePoseGraph graph;
    graph.AddNode(Eigen::Isometry3d::Identity(), Matrix6d::Identity());
    graph.AddNode(PoseFromXYZRPY(10.0, 0.0, 0.0, 0.0, 0.0, 0.0), Matrix6d::Identity());
    // A strong closure says node 1 is really at x = 8.
    graph.AddLoop(0, 1, PoseFromXYZRPY(8.0, 0.0, 0.0, 0.0, 0.0, 0.0), Matrix6d::Identity() * 1e4);
    graph.Finish();
    ASSERT_NEAR(graph.Estimates()[1].translation().x(), 8.0, 0.01);
    graph.AddNode(PoseFromXYZRPY(15.0, 0.0, 0.0, 0.0, 0.0, 0.0), Matrix6d::Identity());
    EXPECT_NEAR(graph.Estimates()[2].translation().x(), 13.0, 0.01);  // 5 m of odometry after the corrected node
    EXPECT_NEAR(graph.OdometryPoses()[2].translation().x(), 15.0, 1e-12);
    EXPECT_THROW(graph.AddLoop(0, 3, Eigen::Isometry3d::Identity(), Matrix6d::Identity()), std::out_of_range);
}

TEST(OnlinePoseGraph, CorrectsDriftOnTheRealKitti00Route) {
    const auto file = std::filesystem::path(REVISIT_SHARED_DIR) / "data/kitti_gt_poses/00.txt";
    if (!std::filesystem::exists(REVISIT_SHARED_DIR) || !std::filesystem::exists(file))
        GTEST_SKIP() << "shared KITTI ground truth not present at " << file;
    const auto truth = testing::ReadKittiRoute(file, 10.0);
    ASSERT_GT(truth.size(), 300u);
    const auto odometry = testing::DriftingOdometry(truth, testing::DriftModel{});
    auto closures = testing::TrueClosures(truth, 8.0, 200.0, 3, kClosureInformation, 17);
    const auto wrong = testing::FalseClosures(truth, static_cast<int>(closures.size() + 8) / 9, 50.0, kClosureInformation, 23);
    const auto clean = RunOnline(odometry, closures, {});
    closures.insert(closures.end(), wrong.begin(), wrong.end());
    const auto run = RunOnline(odometry, closures, {});
    const double before = testing::ApeTranslationRmse(odometry, truth);
    const double clean_after = testing::ApeTranslationRmse(clean.graph.Estimates(), truth);
    const double after = testing::ApeTranslationRmse(run.graph.Estimates(), truth);
    const auto weights = SplitClosureWeights(run.graph, truth);
    ASSERT_EQ(weights.num_wrong, wrong.size());
    std::cout << "[ kitti00 ] " << truth.size() << " nodes, " << closures.size() - wrong.size() << " closures + " << wrong.size()
              << " wrong: APE before " << before << " m, after " << clean_after << " m, with wrong " << after
              << " m, max wrong weight " << weights.max_wrong << ", min right weight " << weights.min_right << "\n";
    EXPECT_LT(clean_after, 0.2 * before);
    EXPECT_LT(after, 1.2 * clean_after);
    EXPECT_LT(weights.max_wrong, 0.01);
    EXPECT_GT(weights.min_right, 0.5);
}

TEST(CorrectTrajectory, ScansMoveRigidlyWithTheirNode) {
    // Three nodes of four scans; optimization moved node 1 by 2 m and turned node 2.
    Poses scans;
    for (int i = 0; i < 12; ++i) scans.push_back(PoseFromXYZRPY(1.0 * i, 0.0, 0.0, 0.0, 0.0, 0.0));
    const auto node_of_scan = NodeOfScan({0, 4, 8}, scans.size());
    EXPECT_EQ(node_of_scan, (std::vector<int>{0, 0, 0, 0, 1, 1, 1, 1, 2, 2, 2, 2}));
    const Poses nodes_odom = {scans[0], scans[4], scans[8]};
    Poses nodes_optimized = nodes_odom;
    nodes_optimized[1].translation().y() += 2.0;
    nodes_optimized[2] = PoseFromXYZRPY(8.0, 0.0, 0.0, 0.0, 0.0, 0.5);
    const auto corrected = CorrectTrajectory(scans, node_of_scan, nodes_odom, nodes_optimized);
    ASSERT_EQ(corrected.size(), scans.size());
    EXPECT_TRUE(corrected[3].isApprox(scans[3]));
    EXPECT_TRUE(corrected[4].isApprox(nodes_optimized[1]));
    EXPECT_NEAR(corrected[6].translation().y(), 2.0, 1e-12);
    // Scan 10 is 2 m ahead of node 2 in the node's frame: it turns with it.
    EXPECT_TRUE(corrected[10].isApprox(nodes_optimized[2] * PoseFromXYZRPY(2.0, 0.0, 0.0, 0.0, 0.0, 0.0)));
}

TEST(CorrectTrajectory, InterpolationRemovesTheJumpBetweenNodes) {
    Poses scans;
    for (int i = 0; i < 8; ++i) scans.push_back(PoseFromXYZRPY(1.0 * i, 0.0, 0.0, 0.0, 0.0, 0.0));
    const auto node_of_scan = NodeOfScan({0, 4}, scans.size());
    const Poses nodes_odom = {scans[0], scans[4]};
    Poses nodes_optimized = nodes_odom;
    nodes_optimized[1].translation().y() = 4.0;
    TrajectoryCorrectionConfig config;
    config.interpolate_between_nodes = true;
    const auto corrected = CorrectTrajectory(scans, node_of_scan, nodes_odom, nodes_optimized, config);
    for (int i = 0; i < 4; ++i) EXPECT_NEAR(corrected[i].translation().y(), 1.0 * i, 1e-9) << i;  // ramps up to node 1
    EXPECT_NEAR(corrected[6].translation().y(), 4.0, 1e-9);  // the last node moves its scans rigidly
}

TEST(CorrectTrajectory, RejectsInconsistentInput) {
    const Poses scans(3, Eigen::Isometry3d::Identity());
    const Poses nodes(1, Eigen::Isometry3d::Identity());
    EXPECT_THROW(CorrectTrajectory(scans, {0, 0}, nodes, nodes), std::invalid_argument);
    EXPECT_THROW(CorrectTrajectory(scans, {0, 0, 1}, nodes, nodes), std::invalid_argument);
    EXPECT_THROW(NodeOfScan({1, 2}, 3), std::invalid_argument);
    EXPECT_THROW(NodeOfScan({0, 2, 2}, 3), std::invalid_argument);
}

TEST(GlobalMapBuilder, PlacesLocalMapsAtTheirNodesOnePointPerVoxel) {
    // The same wall seen from two nodes: once placed, both copies fall into the same voxels.
    std::vector<Eigen::Vector3f> wall_in_world;
    for (int i = 0; i < 100; ++i)
        for (int k = 0; k < 20; ++k) wall_in_world.emplace_back(0.1f * i, 5.2f, 0.1f * k);
    const Poses nodes = {PoseFromXYZRPY(0.0, 0.0, 0.0, 0.0, 0.0, 0.0), PoseFromXYZRPY(4.0, -2.0, 0.0, 0.0, 0.0, 0.7)};
    GlobalMapBuilder builder(0.5);
    for (const auto& T_world_node : nodes) {
        std::vector<Eigen::Vector3f> wall_in_node;
        for (const auto& p : wall_in_world) wall_in_node.push_back((T_world_node.inverse() * p.cast<double>()).cast<float>());
        builder.Add(wall_in_node, T_world_node);
    }
    std::vector<Eigen::Vector3d> placed;
    for (const auto& p : builder.Points()) placed.push_back(p.cast<double>());
    EXPECT_EQ(builder.size(), VoxelDownsample(placed, 0.5).size());  // one point per voxel
    EXPECT_GE(builder.size(), 20u * 4u);
    EXPECT_LE(builder.size(), 20u * 4u + 20u);  // a 10 m x 2 m wall: 20 x 4 voxels, plus rounding at the map border
    for (const auto& p : builder.Points()) EXPECT_NEAR(p.y(), 5.2, 1e-4);
    EXPECT_THROW(GlobalMapBuilder(0.0), ConfigError);
}

TEST(GlobalMapBuilder, PastItsCapTheVoxelDoublesAsIfBuiltAtThatVoxel) {
    // A 40 m x 40 m floor, points 0.25 m apart (at cell centres, away from voxel borders), from two nodes.
    std::vector<Eigen::Vector3f> floor;
    for (int i = 0; i < 160; ++i)
        for (int k = 0; k < 160; ++k) floor.emplace_back(0.125f + 0.25f * i, 0.125f + 0.25f * k, 0.125f);
    const Poses nodes = {Eigen::Isometry3d::Identity(), PoseFromXYZRPY(10.0, 0.0, 0.0, 0.0, 0.0, 0.0)};
    const auto build = [&](double voxel, std::size_t max_points) {
        GlobalMapBuilder builder(voxel, max_points);
        for (const auto& T_world_node : nodes) builder.Add(floor, T_world_node);
        return builder;
    };
    const auto uncapped = build(0.5, 0);
    EXPECT_EQ(uncapped.size(), 100u * 80u);  // 50 m x 40 m at 0.5 m
    const auto capped = build(0.5, 1000);
    EXPECT_DOUBLE_EQ(capped.voxel_size(), 2.0);  // 2,000 points at 1 m, 500 at 2 m
    EXPECT_LE(capped.size(), 1000u);
    const auto direct = build(2.0, 0);
    EXPECT_EQ(capped.Points(), direct.Points());  // the same points, in the same order
    EXPECT_DOUBLE_EQ(build(0.5, 8000).voxel_size(), 0.5);  // a map that fits keeps its voxel
}

TEST(GlobalMapBuilder, KeepsTheFirstPointOfEachVoxelInOrderWhereverThePointsLie) {
    // Points anywhere (also on voxel borders), from three nodes turned and shifted, and maps of
    // different sizes: the capped map is the first written point of each voxel at its final voxel,
    // in the order the points came, as a plain ordered map of voxels says.
    std::mt19937 random(7);
    std::uniform_real_distribution<float> coordinate(-12.0f, 12.0f);
    std::vector<std::vector<Eigen::Vector3f>> maps(3);
    for (std::size_t m = 0; m < maps.size(); ++m)
        for (std::size_t i = 0; i < 3000 * (m + 1); ++i) maps[m].emplace_back(coordinate(random), coordinate(random), 0.2f * coordinate(random));
    const Poses nodes = {Eigen::Isometry3d::Identity(), PoseFromXYZRPY(3.0, -1.5, 0.2, 0.0, 0.0, 0.9),
                         PoseFromXYZRPY(-4.0, 6.0, 0.0, 0.1, 0.0, -2.0)};
    GlobalMapBuilder capped(0.25, 2500);
    for (std::size_t m = 0; m < maps.size(); ++m) capped.Add(maps[m], nodes[m]);
    EXPECT_GT(capped.voxel_size(), 0.25);
    EXPECT_LE(capped.size(), 2500u);

    std::vector<Eigen::Vector3f> expected;
    std::set<std::array<int, 3>> seen;
    for (std::size_t m = 0; m < maps.size(); ++m) {
        for (const auto& p : maps[m]) {
            const Eigen::Vector3f written = (nodes[m] * p.cast<double>()).cast<float>();
            const Voxel v = VoxelOf(written.cast<double>(), capped.voxel_size());
            if (seen.insert({v.x(), v.y(), v.z()}).second) expected.push_back(written);
        }
    }
    EXPECT_EQ(capped.Points(), expected);
    // Half the final voxel would not have fitted.
    std::set<std::array<int, 3>> finer;
    for (std::size_t m = 0; m < maps.size(); ++m)
        for (const auto& p : maps[m]) {
            const Voxel v = VoxelOf((nodes[m] * p.cast<double>()).cast<float>().cast<double>(), 0.5 * capped.voxel_size());
            finer.insert({v.x(), v.y(), v.z()});
        }
    EXPECT_GT(finer.size(), 2500u);
}

}  // namespace
}  // namespace revisit
