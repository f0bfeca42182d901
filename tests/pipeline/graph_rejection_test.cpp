/// A closure the pose graph rejects (robust weight below graph_noise.min_weight) must not move the
/// corrected trajectory: nearly off is not off. Measured before the fix on a simulated corridor: one such
/// closure at weight 0.097 pulled the trajectory 10 m along (APE 0.04 -> 10.65 m) while the summary
/// called it rejected.
#include <gtest/gtest.h>

#include "optimization/pose_graph.hpp"
#include "settings/auto_settings.hpp"
#include "pipeline_run.hpp"

namespace revisit {
namespace {

/// The final pose graph rebuilt from the run's records: the odometry between map origins and the
/// accepted closures only, with the settings the run ended with.
Poses OptimizeAcceptedOnly(const RunState& state, PipelineConfig config) {
    for (const auto& update : state.setting_updates)
        if (update.key == "graph.odometry_rotation_per_m") config.graph_noise.odometry_rotation_per_m = update.to;
    const auto& noise = config.graph_noise;
    Poses nodes;
    for (const auto& map : state.maps) nodes.push_back(map.T_world_map);
    OdometryNoise odometry_noise;
    odometry_noise.translation_per_m = noise.odometry_translation_per_m;
    odometry_noise.rotation_per_m = noise.odometry_rotation_per_m;
    std::vector<PoseGraphEdge> edges;
    for (std::size_t i = 1; i < nodes.size(); ++i) {
        const double travel = state.maps[i].travel_start - state.maps[i - 1].travel_start;
        edges.push_back({int(i - 1), int(i), nodes[i - 1].inverse() * nodes[i], OdometryInformation(travel, odometry_noise), false});
    }
    for (const auto& record : state.closures) {
        if (!record.accepted || !CorrectsTrajectory(record)) continue;
        PoseGraphEdge edge;
        edge.from = record.closure.query_id;
        edge.to = record.closure.ref_id;
        edge.T_from_to = record.refinement.T_query_ref;
        edge.is_loop = true;
        edge.information = noise.closure_information_from_registration && record.refinement.information.trace() > 0
                               ? record.refinement.information
                               : DiagonalInformation(noise.closure_sigma_translation, noise.closure_sigma_rotation);
        edges.push_back(edge);
    }
    return OptimizePoseGraph(nodes, edges, config.graph).T_world_node;
}

TEST(GraphRejection, AClosureTheGraphRejectsNoLongerMovesTheTrajectory) {
    const auto log_file = test::SharedData("radish/intel.rawlog");
    REVISIT_REQUIRE_DATA(log_file);
    // With the prior's heading bias removed and maps stored at 4 cm, intel's closures include some the
    // graph weights below 0.1 (measured: 3). Which ones is a matter of the maps' points: at
    // the derived 10 cm, since the maps are stored on their grid, none.
    PipelineConfig config = LoadConfig({}, {"odometry.prior_bias_correction=true", "output.map_voxel=0.04", "output.write_report=false",
                                            "output.scan_context=false", "output.elevation_ablation=false"});
    ConfigureFromData(config, log_file);
    const RunState state = test::RunQuietly(log_file, config);

    std::size_t rejected_by_graph = 0, accepted = 0;
    for (const auto& record : state.closures) {
        if (record.reason.rfind("inconsistent with the pose graph", 0) == 0) {
            ++rejected_by_graph;
            EXPECT_FALSE(record.accepted);
            EXPECT_LT(record.graph_weight, config.graph_noise.min_weight);
        }
        if (record.accepted) {
            ++accepted;
            EXPECT_GE(record.graph_weight, config.graph_noise.min_weight);
        }
    }
    ASSERT_GE(rejected_by_graph, 1u) << "the case this test needs did not occur";
    EXPECT_GE(accepted, 40u);  // measured 99

    const Poses expected = OptimizeAcceptedOnly(state, config);
    ASSERT_EQ(expected.size(), state.maps.size());
    double largest = 0.0;
    for (std::size_t m = 0; m < expected.size(); ++m)
        largest = std::max(largest, (expected[m].translation() - state.maps[m].T_world_map_corrected.translation()).norm());
    EXPECT_LT(largest, 1e-3) << "the corrected map origins differ from a graph of the accepted closures by up to " << largest << " m";
}

}  // namespace
}  // namespace revisit
