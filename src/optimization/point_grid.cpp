#include "optimization/point_grid.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_set>

#include "core/error.hpp"

namespace revisit {
namespace {
void RequirePositive(double value, const char* name) {
    if (!(value > 0.0)) throw ConfigError(std::string(name) + " must be positive");
}
}  // namespace

double VoxelOverlap(const std::vector<Eigen::Vector3d>& a, const std::vector<Eigen::Vector3d>& b, double voxel_size) {
    RequirePositive(voxel_size, "voxel_size");
    std::unordered_set<Eigen::Vector3i, VoxelHash> voxels_a;
    for (const auto& point : a) voxels_a.insert(VoxelOf(point, voxel_size));
    std::unordered_set<Eigen::Vector3i, VoxelHash> voxels_b;
    for (const auto& point : b) voxels_b.insert(VoxelOf(point, voxel_size));
    if (voxels_a.empty() || voxels_b.empty()) return 0.0;
    const auto& smaller = voxels_a.size() <= voxels_b.size() ? voxels_a : voxels_b;
    const auto& larger = voxels_a.size() <= voxels_b.size() ? voxels_b : voxels_a;
    const auto common = std::count_if(smaller.begin(), smaller.end(), [&](const Eigen::Vector3i& key) {
        return larger.count(key) > 0;
    });
    return static_cast<double>(common) / static_cast<double>(smaller.size());
}


PointGrid::PointGrid(const std::vector<Eigen::Vector3d>& points, double cell_size)
    : points_(points), cell_size_(cell_size) {
    RequirePositive(cell_size, "cell_size");
    cells_.reserve(points_.size() / 2 + 1);
    for (std::size_t i = 0; i < points_.size(); ++i) cells_[VoxelOf(points_[i], cell_size_)].push_back(static_cast<int>(i));
}

int PointGrid::FindNearest(const Eigen::Vector3d& query, double max_distance) const {
    int best = -1;
    double best_squared = max_distance * max_distance;
    ForEachNeighbour(query, max_distance, [&](int index) {
        const double squared = (points_[index] - query).squaredNorm();
        if (squared <= best_squared) {
            best_squared = squared;
            best = index;
        }
    });
    return best;
}

std::vector<int> PointGrid::FindWithin(const Eigen::Vector3d& query, double radius) const {
    std::vector<int> found;
    ForEachWithin(query, radius, [&](int index) { found.push_back(index); });
    return found;
}

}  // namespace revisit
