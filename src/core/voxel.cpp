#include "core/voxel.hpp"

#include <tsl/robin_set.h>

#include "core/error.hpp"

namespace revisit {

std::vector<Eigen::Vector3d> VoxelDownsample(const std::vector<Eigen::Vector3d>& points, double voxel_size) {
    if (!(voxel_size > 0.0)) throw ConfigError("voxel_size must be positive");
    const double inv_voxel_size = 1.0 / voxel_size;
    tsl::robin_set<Voxel, VoxelHash> seen;
    seen.reserve(points.size() / 2);
    std::vector<Eigen::Vector3d> kept;
    kept.reserve(points.size() / 2);
    for (const auto& point : points) {
        const Voxel voxel = VoxelOfInverse(point, inv_voxel_size);
        if (seen.insert(voxel).second) kept.push_back(point);
    }
    return kept;
}

}  // namespace revisit
