#pragma once
/// A sequence of stamped poses: ground truth, odometry, or a corrected trajectory.
#include <Eigen/Geometry>
#include <vector>

namespace revisit {

using Poses = std::vector<Eigen::Isometry3d>;

struct Trajectory {
    std::vector<double> timestamps;  ///< [s], same length as poses (may be empty for KITTI files without times)
    Poses poses;                     ///< T_world_sensor per entry

    std::size_t size() const { return poses.size(); }
    bool empty() const { return poses.empty(); }
    bool has_timestamps() const { return timestamps.size() == poses.size() && !poses.empty(); }
};

/// Sum of distances between consecutive positions [m].
double PathLength(const Poses& poses);

/// Cumulative travelled distance at each pose [m]; first entry 0.
std::vector<double> CumulativeDistance(const Poses& poses);

}  // namespace revisit
