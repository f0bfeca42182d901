#pragma once
/// The corrected trajectory: every scan pose re-anchored to its optimized node (METHOD.md section 6).
#include <vector>

#include "core/trajectory.hpp"

namespace revisit {

struct TrajectoryCorrectionConfig {
    /// false: every scan moves rigidly with its node (METHOD.md). true: the correction is blended
    /// (SE(3) geodesic) from the scan's node to the next one by travelled distance, so the
    /// corrected trajectory has no jump where one local map hands over to the next.
    bool interpolate_between_nodes = false;
};

/// Node index of every scan, given the first scan index of each node (ascending; the first
/// must be 0). Throws std::invalid_argument otherwise.
std::vector<int> NodeOfScan(const std::vector<std::size_t>& first_scan_of_node, std::size_t num_scans);

/// T_world_scan_corrected = T_world_node_optimized * T_world_node_odom^-1 * T_world_scan_odom.
/// Throws std::invalid_argument when sizes disagree or a node index is out of range.
Poses CorrectTrajectory(const Poses& T_world_scan_odom, const std::vector<int>& node_of_scan, const Poses& T_world_node_odom,
                        const Poses& T_world_node_optimized, const TrajectoryCorrectionConfig& config = {});

}  // namespace revisit
