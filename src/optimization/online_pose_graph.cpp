#include "optimization/online_pose_graph.hpp"

#include <stdexcept>
#include <string>

namespace revisit {

OnlinePoseGraph::OnlinePoseGraph(const OnlinePoseGraphConfig& config) : config_(config) {}

int OnlinePoseGraph::AddNode(const Eigen::Isometry3d& T_world_node_odom, const Matrix6d& odometry_information) {
    if (T_world_node_.empty()) {
        T_world_node_.push_back(T_world_node_odom);
    } else {
        const Eigen::Isometry3d T_previous_node = T_world_node_odom_.back().inverse() * T_world_node_odom;
        T_world_node_.push_back(T_world_node_.back() * T_previous_node);
        const int to = static_cast<int>(T_world_node_.size()) - 1;
        edges_.push_back({to - 1, to, T_previous_node, odometry_information, false});
    }
    T_world_node_odom_.push_back(T_world_node_odom);
    return static_cast<int>(T_world_node_.size()) - 1;
}

std::size_t OnlinePoseGraph::AddLoop(int from, int to, const Eigen::Isometry3d& T_from_to, const Matrix6d& information) {
    const int num_nodes = static_cast<int>(T_world_node_.size());
    if (from < 0 || to < 0 || from >= num_nodes || to >= num_nodes || from == to)
        throw std::out_of_range("loop closure between nodes " + std::to_string(from) + " and " + std::to_string(to) + " of " +
                                std::to_string(num_nodes));
    edges_.push_back({from, to, T_from_to, information, true});
    return edges_.size() - 1;
}

const PoseGraphResult& OnlinePoseGraph::Update() {
    PoseGraphConfig config = config_.batch;
    config.max_time_s = config_.update_max_time_s;
    config.max_iterations = config_.update_max_iterations;
    return Optimize(config);
}

const PoseGraphResult& OnlinePoseGraph::Finish() { return Optimize(config_.batch); }

const PoseGraphResult& OnlinePoseGraph::Optimize(const PoseGraphConfig& config) {
    last_result_ = OptimizePoseGraph(T_world_node_, edges_, config);
    T_world_node_ = last_result_.T_world_node;
    return last_result_;
}

}  // namespace revisit
