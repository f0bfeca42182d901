#pragma once
/// A run's final pose graph in g2o's text format, for the pose-graph back ends users already have
/// (g2o, the ceres-solver pose_graph_3d example's reader, GTSAM's readG2o).
#include <ostream>
#include <vector>

#include "config/config.hpp"
#include "optimization/pose_graph.hpp"
#include "runfolder/run_state.hpp"

namespace revisit {

/// Nodes with their odometry poses (the optimizer's starting point) and every edge it used.
struct ExportGraph {
    Poses T_world_node;
    std::vector<PoseGraphEdge> edges;  ///< odometry first, in node order, then the accepted closures
    std::vector<std::size_t> closure_of_edge;  ///< per loop edge (in order): its index in state.closures
    bool planar = false;                ///< a 2D laser's run: x, y, yaw only
};

/// The information matrix the graph gave an accepted closure (pipeline/online.cpp's rule): the
/// registration's when the config asks for it and the registration gave one, else the fixed sigmas.
Matrix6d ClosureInformation(const ClosureRecord& record, const GraphNoiseConfig& noise);

/// The graph the final optimization solved: one node per local map (T_world_map, the odometry's), one
/// odometry edge per consecutive pair (information from the travel between them), one loop edge per
/// accepted closure, from the query map to the reference map. `per_scan`: one node per scan instead,
/// odometry edges between consecutive scans (the same noise model per metre), closures between the
/// maps' first scans (the maps' origins).
ExportGraph RunPoseGraph(const RunState& state, const PipelineConfig& config, bool per_scan);

/// g2o's text format: VERTEX_SE3:QUAT / EDGE_SE3:QUAT (planar: VERTEX_SE2 / EDGE_SE2), information as
/// the upper triangle row by row. g2o's SE(3) error takes the quaternion's vector part where revisit's
/// graph takes twice it, so the rotation rows and columns are scaled to keep every chi^2 the same.
void WriteG2o(std::ostream& out, const ExportGraph& graph);

}  // namespace revisit
