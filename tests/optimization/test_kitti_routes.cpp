#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <iostream>
#include <string>

#include "optimization/drift_simulation.hpp"
#include "optimization/pose_graph.hpp"

namespace revisit {
namespace {

/// Real KITTI routes (00: 3.7 km, 05: 2.2 km, 06: 1.2 km) with simulated drifting odometry,
/// closures where the route revisits itself, and 10% wrong closures of plausible size.
class KittiRoute : public ::testing::TestWithParam<std::string> {};

TEST_P(KittiRoute, ClosuresCorrectTheDriftAndWrongOnesAreIgnored) {
    const auto file = std::filesystem::path(REVISIT_SHARED_DIR) / "data/kitti_gt_poses" / (GetParam() + ".txt");
    if (!std::filesystem::exists(REVISIT_SHARED_DIR) || !std::filesystem::exists(file))
        GTEST_SKIP() << "shared KITTI ground truth not present at " << file;
    const auto truth = testing::ReadKittiRoute(file, 10.0);
    ASSERT_GT(truth.size(), 100u);
    const Matrix6d closure_information = DiagonalInformation(0.1, 0.005);
    const auto odometry = testing::DriftingOdometry(truth, testing::DriftModel{});
    auto edges = OdometryEdges(odometry, DiagonalInformation(0.1, 0.003));
    const auto closures = testing::TrueClosures(truth, 8.0, 200.0, 3, closure_information, 17);
    edges.insert(edges.end(), closures.begin(), closures.end());
    const auto clean = OptimizePoseGraph(odometry, edges, PoseGraphConfig{});

    const auto wrong = testing::FalseClosures(truth, static_cast<int>(closures.size() + 8) / 9, 50.0, closure_information, 23);
    edges.insert(edges.end(), wrong.begin(), wrong.end());
    const auto result = OptimizePoseGraph(odometry, edges, PoseGraphConfig{});
    const double max_wrong_weight = *std::max_element(result.edge_weights.end() - static_cast<std::ptrdiff_t>(wrong.size()), result.edge_weights.end());

    const double before = testing::ApeTranslationRmse(odometry, truth);
    const double after = testing::ApeTranslationRmse(clean.T_world_node, truth);
    const double after_with_wrong = testing::ApeTranslationRmse(result.T_world_node, truth);
    std::cout << "[ kitti" << GetParam() << " ] " << truth.size() << " nodes, " << PathLength(truth) << " m, " << closures.size()
              << " closures: APE before " << before << " m, after " << after << " m; +" << wrong.size() << " wrong: "
              << after_with_wrong << " m, max wrong weight " << max_wrong_weight << "\n";
    EXPECT_LT(after, 0.25 * before);  // measured 81-94% reduction over the three routes
    EXPECT_LT(after_with_wrong, 1.2 * after);
    EXPECT_LT(max_wrong_weight, 0.01);
}

INSTANTIATE_TEST_SUITE_P(Sequences, KittiRoute, ::testing::Values("00", "05", "06"));

}  // namespace
}  // namespace revisit
