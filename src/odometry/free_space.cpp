#include "odometry/free_space.hpp"

#include <cmath>

namespace revisit {

std::uint64_t FreeSpace2D::Key(const Eigen::Vector3d& point) const {
    const auto x = static_cast<std::int32_t>(std::floor(point.x() / cell_));
    const auto y = static_cast<std::int32_t>(std::floor(point.y() / cell_));
    return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(x)) << 32) | static_cast<std::uint32_t>(y);
}

void FreeSpace2D::AddBeams(const Eigen::Vector3d& origin, const std::vector<Eigen::Vector3d>& returns_in_world, double margin) {
    // Half-cell steps visit every cell a beam crosses but those it only clips at a corner.
    const double step = 0.5 * cell_;
    for (const Eigen::Vector3d& end : returns_in_world) {
        Eigen::Vector3d direction = end - origin;
        direction.z() = 0.0;
        const double length = direction.norm() - margin;
        if (length <= 0.0) continue;
        direction /= length + margin;
        for (double s = 0.0; s < length; s += step) cells_.insert(Key(origin + s * direction));
    }
}

void FreeSpace2D::RemoveFarFrom(const Eigen::Vector3d& origin, double radius) {
    if (cells_.size() < 2 * kept_ + 1024) return;
    const double reach = radius + cell_;
    for (auto it = cells_.begin(); it != cells_.end();) {
        const double x = (static_cast<double>(static_cast<std::int32_t>(*it >> 32)) + 0.5) * cell_ - origin.x();
        const double y = (static_cast<double>(static_cast<std::int32_t>(*it & 0xffffffffu)) + 0.5) * cell_ - origin.y();
        if (x * x + y * y > reach * reach)
            it = cells_.erase(it);
        else
            ++it;
    }
    kept_ = cells_.size();
}

BeamConflicts CountBeamConflicts(const FreeSpace2D& free, const VoxelHashMap& map, const std::vector<Eigen::Vector3d>& points_in_sensor,
                                 const Eigen::Isometry3d& T_world_sensor, double margin) {
    BeamConflicts conflicts;
    const double cell = free.cell();
    const Eigen::Vector3d origin = T_world_sensor.translation();
    for (const Eigen::Vector3d& point : points_in_sensor) {
        const Eigen::Vector3d end = T_world_sensor * point;
        if (free.Free(end) && map.FindNearest(end, cell) == nullptr) ++conflicts.returns_in_free;
        const double range = point.head<2>().norm();
        const double length = range - margin;
        if (length <= 0.0) continue;
        Eigen::Vector3d direction = end - origin;
        direction /= range;
        for (double s = 0.5 * cell; s < length; s += 0.5 * cell) {
            if (map.FindNearest(origin + s * direction, 0.5 * cell) != nullptr) {
                ++conflicts.beams_through_walls;
                break;
            }
        }
    }
    return conflicts;
}

}  // namespace revisit
