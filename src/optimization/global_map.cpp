#include "optimization/global_map.hpp"

#include "core/error.hpp"

namespace revisit {

GlobalMapBuilder::GlobalMapBuilder(double voxel_size) : voxel_size_(voxel_size) {
    if (!(voxel_size > 0.0)) throw ConfigError("global map: voxel_size must be positive");
    occupied_.max_load_factor(0.9f);
}

void GlobalMapBuilder::Insert(const Eigen::Vector3d& point_in_world) {
    if (occupied_.insert(VoxelOf(point_in_world, voxel_size_)).second) points_.push_back(point_in_world.cast<float>());
}

}  // namespace revisit
