#include "optimization/global_map.hpp"

#include "core/error.hpp"

namespace revisit {

GlobalMapBuilder::GlobalMapBuilder(double voxel_size, std::size_t max_points) : voxel_size_(voxel_size), max_points_(max_points) {
    if (!(voxel_size > 0.0)) throw ConfigError("global map: voxel_size must be positive");
    occupied_.max_load_factor(0.9f);
}

void GlobalMapBuilder::Insert(const Eigen::Vector3d& point_in_world) {
    if (!occupied_.insert(VoxelOf(point_in_world, voxel_size_)).second) return;
    points_.push_back(point_in_world.cast<float>());
    while (max_points_ > 0 && points_.size() > max_points_) Coarsen();
}

void GlobalMapBuilder::Coarsen() {
    voxel_size_ *= 2.0;
    occupied_ = tsl::robin_set<Voxel, MixedVoxelHash>();  // release the old table before the new one grows
    occupied_.max_load_factor(0.9f);
    // In insertion order: the earliest of the points kept in a new voxel's eight old voxels is the first
    // point that reached it.
    std::vector<Eigen::Vector3f> kept;
    for (const auto& point : points_) {
        if (occupied_.insert(VoxelOf(point.cast<double>(), voxel_size_)).second) kept.push_back(point);
    }
    points_ = std::move(kept);
}

}  // namespace revisit
