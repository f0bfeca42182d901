#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <vector>

#include "exports/pose_graph_export.hpp"

namespace revisit {
namespace {

std::vector<std::vector<std::string>> Lines(const std::string& text) {
    std::vector<std::vector<std::string>> lines;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) {
        std::istringstream fields(line);
        std::vector<std::string> words;
        for (std::string w; fields >> w;) words.push_back(w);
        lines.push_back(words);
    }
    return lines;
}

/// Two map origins 10 m apart with a quarter turn, an odometry edge and a closure with a known information.
RunState TwoMaps() {
    RunState state;
    MapRecordSummary a, b;
    a.id = 0;
    b.id = 1;
    b.first_scan = 5;
    b.last_scan = 9;
    a.last_scan = 4;
    b.T_world_map = Eigen::Translation3d(10.0, 0.0, 0.0) * Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ());
    b.travel_start = 10.0;
    state.maps = {a, b};
    ClosureRecord closure;
    closure.accepted = true;
    closure.closure.query_id = 1;
    closure.closure.ref_id = 0;
    closure.refinement.T_query_ref = b.T_world_map.inverse();
    ClosureRecord rejected = closure;
    rejected.accepted = false;
    state.closures = {rejected, closure};
    return state;
}

TEST(WriteG2o, Se3VerticesEdgesAndInformationInG2oConvention) {
    PipelineConfig config;
    const ExportGraph graph = RunPoseGraph(TwoMaps(), config, false);
    ASSERT_EQ(graph.edges.size(), 2u);  // the odometry edge and the accepted closure only
    std::ostringstream out;
    WriteG2o(out, graph);
    const auto lines = Lines(out.str());
    ASSERT_EQ(lines.size(), 4u);
    ASSERT_EQ(lines[1].size(), 9u);
    EXPECT_EQ(lines[1][0], "VERTEX_SE3:QUAT");
    EXPECT_DOUBLE_EQ(std::stod(lines[1][2]), 10.0);
    EXPECT_NEAR(std::stod(lines[1][7]), std::sqrt(0.5), 1e-12);  // qz of a quarter turn
    EXPECT_NEAR(std::stod(lines[1][8]), std::sqrt(0.5), 1e-12);  // qw
    ASSERT_EQ(lines[3].size(), 1u + 2 + 7 + 21);
    EXPECT_EQ(lines[3][0], "EDGE_SE3:QUAT");
    EXPECT_EQ(lines[3][1], "1");
    EXPECT_EQ(lines[3][2], "0");
    // The upper triangle row by row: entry (0,0) first, (3,3) at 6 + 5 + 4 = 15, (5,5) last.
    const double sigma_t = config.graph_noise.closure_sigma_translation, sigma_r = config.graph_noise.closure_sigma_rotation;
    EXPECT_NEAR(std::stod(lines[3][10]), 1.0 / (sigma_t * sigma_t), 1e-6);
    EXPECT_NEAR(std::stod(lines[3][10 + 15]), 4.0 / (sigma_r * sigma_r), 1e-6);  // g2o's error is half of revisit's
    EXPECT_NEAR(std::stod(lines[3][10 + 20]), 4.0 / (sigma_r * sigma_r), 1e-6);
    EXPECT_EQ(std::stod(lines[3][11]), 0.0);
}

TEST(WriteG2o, PlanarRunsWriteSe2WithYaw) {
    PipelineConfig config;
    config.odometry.planar = true;
    std::ostringstream out;
    WriteG2o(out, RunPoseGraph(TwoMaps(), config, false));
    const auto lines = Lines(out.str());
    ASSERT_EQ(lines.size(), 4u);
    ASSERT_EQ(lines[1].size(), 5u);
    EXPECT_EQ(lines[1][0], "VERTEX_SE2");
    EXPECT_NEAR(std::stod(lines[1][4]), M_PI / 2, 1e-12);
    ASSERT_EQ(lines[3].size(), 1u + 2 + 3 + 6);
    EXPECT_EQ(lines[3][0], "EDGE_SE2");
    EXPECT_NEAR(std::stod(lines[3][5]), -M_PI / 2, 1e-12);
    const double sigma_r = config.graph_noise.closure_sigma_rotation;
    EXPECT_NEAR(std::stod(lines[3][6 + 5]), 1.0 / (sigma_r * sigma_r), 1e-6);  // (yaw, yaw), last of the triangle
}

TEST(RunPoseGraph, PerScanClosuresJoinTheMapsFirstScans) {
    RunState state = TwoMaps();
    state.odometry.assign(10, Eigen::Isometry3d::Identity());
    const ExportGraph graph = RunPoseGraph(state, PipelineConfig{}, true);
    EXPECT_EQ(graph.T_world_node.size(), 10u);
    ASSERT_EQ(graph.edges.size(), 9u + 1u);
    EXPECT_EQ(graph.edges.back().from, 5);
    EXPECT_EQ(graph.edges.back().to, 0);
}

}  // namespace
}  // namespace revisit
