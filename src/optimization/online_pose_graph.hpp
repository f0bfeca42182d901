#pragma once
/// The pose graph as a robot grows it: nodes as local maps start, closures as they are
/// accepted, a bounded-time update after each, and one final batch optimization.
#include <Eigen/Geometry>
#include <vector>

#include "optimization/pose_graph.hpp"

namespace revisit {

struct OnlinePoseGraphConfig {
    PoseGraphConfig batch;              ///< the final optimization (Finish)
    double update_max_time_s = 0.05;    ///< [s] wall-time bound of each Update
    int update_max_iterations = 20;     ///< Ceres iterations bound of each Update
};

class OnlinePoseGraph {
  public:
    explicit OnlinePoseGraph(const OnlinePoseGraphConfig& config = {});

    /// Adds a node at its odometry pose and the odometry edge from the previous node; returns
    /// its id. Its estimate continues from the previous node's optimized pose, so the graph
    /// stays corrected as it grows.
    int AddNode(const Eigen::Isometry3d& T_world_node_odom, const Matrix6d& odometry_information);
    /// Adds an accepted closure (T_from_to: pose of `to` in `from`, e.g. from = query map,
    /// to = reference map, T_from_to = refined T_query_ref); returns the edge index.
    /// Throws std::out_of_range for unknown nodes.
    std::size_t AddLoop(int from, int to, const Eigen::Isometry3d& T_from_to, const Matrix6d& information);

    /// Bounded-time optimization from the current estimates (run when closures arrive).
    const PoseGraphResult& Update();
    /// Final batch optimization from the current estimates, without the time bound.
    const PoseGraphResult& Finish();

    const Poses& Estimates() const { return T_world_node_; }
    const Poses& OdometryPoses() const { return T_world_node_odom_; }
    const std::vector<PoseGraphEdge>& Edges() const { return edges_; }
    /// The latest optimization's report (empty before the first Update/Finish).
    const PoseGraphResult& LastResult() const { return last_result_; }
    std::size_t size() const { return T_world_node_.size(); }

  private:
    const PoseGraphResult& Optimize(const PoseGraphConfig& config);

    OnlinePoseGraphConfig config_;
    Poses T_world_node_odom_;
    Poses T_world_node_;
    std::vector<PoseGraphEdge> edges_;
    PoseGraphResult last_result_;
};

}  // namespace revisit
