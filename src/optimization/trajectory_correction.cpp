#include "optimization/trajectory_correction.hpp"

#include <stdexcept>
#include <string>

#include "core/se3.hpp"

namespace revisit {

std::vector<int> NodeOfScan(const std::vector<std::size_t>& first_scan_of_node, std::size_t num_scans) {
    if (first_scan_of_node.empty() || first_scan_of_node.front() != 0)
        throw std::invalid_argument("NodeOfScan: the first node must start at scan 0");
    for (std::size_t n = 1; n < first_scan_of_node.size(); ++n) {
        if (first_scan_of_node[n] <= first_scan_of_node[n - 1])
            throw std::invalid_argument("NodeOfScan: first scans must be strictly ascending (node " + std::to_string(n) + ")");
    }
    std::vector<int> node_of_scan(num_scans, 0);
    std::size_t node = 0;
    for (std::size_t i = 0; i < num_scans; ++i) {
        while (node + 1 < first_scan_of_node.size() && first_scan_of_node[node + 1] <= i) ++node;
        node_of_scan[i] = static_cast<int>(node);
    }
    return node_of_scan;
}

Poses CorrectTrajectory(const Poses& T_world_scan_odom, const std::vector<int>& node_of_scan, const Poses& T_world_node_odom,
                        const Poses& T_world_node_optimized, const TrajectoryCorrectionConfig& config) {
    if (node_of_scan.size() != T_world_scan_odom.size())
        throw std::invalid_argument("CorrectTrajectory: " + std::to_string(node_of_scan.size()) + " node indices for " +
                                    std::to_string(T_world_scan_odom.size()) + " scans");
    if (T_world_node_odom.size() != T_world_node_optimized.size())
        throw std::invalid_argument("CorrectTrajectory: odometry and optimized node counts differ");
    const int num_nodes = static_cast<int>(T_world_node_odom.size());
    // Left correction of each node: what optimization did to it, in the world frame.
    Poses correction(T_world_node_odom.size());
    for (int n = 0; n < num_nodes; ++n) correction[n] = T_world_node_optimized[n] * T_world_node_odom[n].inverse();

    // Travelled distance at each node's first scan, for blending (-1: node has no scan).
    const auto travel = CumulativeDistance(T_world_scan_odom);
    std::vector<double> node_start(T_world_node_odom.size(), -1.0);
    for (std::size_t i = 0; i < node_of_scan.size(); ++i) {
        const int n = node_of_scan[i];
        if (n < 0 || n >= num_nodes)
            throw std::invalid_argument("CorrectTrajectory: scan " + std::to_string(i) + " names node " + std::to_string(n) +
                                        " of " + std::to_string(num_nodes));
        if (node_start[n] < 0.0) node_start[n] = travel[i];
    }

    Poses corrected(T_world_scan_odom.size());
    for (std::size_t i = 0; i < T_world_scan_odom.size(); ++i) {
        const int n = node_of_scan[i];
        Eigen::Isometry3d T_correction = correction[n];
        const bool has_next = n + 1 < num_nodes && node_start[n + 1] > node_start[n];
        if (config.interpolate_between_nodes && has_next) {
            const double fraction = (travel[i] - node_start[n]) / (node_start[n + 1] - node_start[n]);
            if (fraction > 0.0 && fraction < 1.0)
                T_correction = correction[n] * ExpSE3(fraction * LogSE3(correction[n].inverse() * correction[n + 1]));
        }
        corrected[i] = T_correction * T_world_scan_odom[i];
    }
    return corrected;
}

}  // namespace revisit
