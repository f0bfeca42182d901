// The recent-travel check of a 2D laser's odometry without wheel odometry (docs/method.md, "2D
// odometry without wheel odometry").
//
// A scan that sees a place an earlier pass mapped finds that pass in the odometry's map where the
// drift put it, and a registration to the whole map may pull the scan onto the drifted copy: a loop
// closed inside the odometry, unchecked. Dropping the old voxels (odometry.map_travel_horizon) removes
// that pull, but also what tells a corridor's aliases apart (doors at regular spacing): the earlier
// pass is what makes one of the equally good poses on the recent travel the right one. So both
// registrations are made, and the recent travel judges them: the whole map's pose is kept unless the
// recent travel's own pose explains the scan clearly better against the recent voxels. Aliases on the
// recent travel explain it about equally, and the whole map decides among them; a pull onto a drifted
// copy leaves the scan's recent walls behind, which the recent voxels measure.
#include <cmath>

#include "odometry/lidar_odometry.hpp"

namespace revisit {
void LidarOdometry::CheckRecentTravel(const std::vector<Eigen::Vector3d>& source, const Eigen::Isometry3d& last_pose,
                                      const Eigen::Isometry3d& delta, Eigen::Isometry3d& T_start, Eigen::Isometry3d& T_new) {
    // Nothing older than the recent travel within the map's radius: both maps are the same.
    if (recent_map_.Empty() || recent_map_.NumVoxels() == map_.NumVoxels()) return;
    // The earlier pass can only have pulled the frame when it explains points the recent voxels do not:
    // otherwise the second registration is not needed (most frames; it costs a correlative match).
    const double voxel = config_.VoxelSize();
    const double whole = static_cast<double>(CountAgreeing(recent_map_, source, T_new, voxel, 1));
    const double whole_on_map = static_cast<double>(CountAgreeing(map_, source, T_new, voxel, 1));
    if (!ClearlyMore(whole_on_map, whole)) return;
    const OdometryFrameStats whole_map_stats = stats_;
    double resolution = 0.0;
    const Eigen::Isometry3d T_recent_start = CorrelativeStart(recent_map_, source, last_pose, delta, resolution);
    Eigen::Isometry3d T_recent = T_new;
    const bool registered = RegisterFrom(recent_map_, source, T_recent_start, delta, last_pose, false, resolution, T_recent).empty();
    const OdometryFrameStats recent_stats = stats_;
    stats_ = whole_map_stats;
    if (!registered) return;
    const double recent = static_cast<double>(CountAgreeing(recent_map_, source, T_recent, voxel, 1));
    if (!ClearlyMore(recent, whole)) return;
    stats_ = recent_stats;
    stats_.recent_travel_used = true;
    T_start = T_recent_start;
    T_new = T_recent;
}

}  // namespace revisit
