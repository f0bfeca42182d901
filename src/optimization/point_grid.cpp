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


PointGrid::PointGrid(const std::vector<Eigen::Vector3d>& points, double cell_size) : cell_size_(cell_size) {
    RequirePositive(cell_size, "cell_size");
    // Cells numbered by first appearance; counting sort keeps ascending indices within a cell.
    std::vector<std::uint32_t> cell_of(points.size());
    cells_.reserve(points.size() / 2 + 1);
    std::vector<std::size_t> counts;
    for (std::size_t i = 0; i < points.size(); ++i) {
        const Voxel key = VoxelOf(points[i], cell_size_);
        const auto [it, inserted] = cells_.try_emplace(key, static_cast<std::uint32_t>(cell_keys_.size()));
        if (inserted) {
            cell_keys_.push_back(key);
            counts.push_back(0);
        }
        cell_of[i] = it->second;
        ++counts[it->second];
    }
    offsets_.assign(cell_keys_.size() + 1, 0);
    for (std::size_t c = 0; c < counts.size(); ++c) offsets_[c + 1] = offsets_[c] + counts[c];
    std::vector<std::size_t> next(offsets_.begin(), offsets_.end() - 1);
    sorted_points_.resize(points.size());
    index_.resize(points.size());
    for (std::size_t i = 0; i < points.size(); ++i) {
        const std::size_t slot = next[cell_of[i]]++;
        sorted_points_[slot] = points[i];
        index_[slot] = static_cast<int>(i);
    }
}

void PointGrid::NeighbourCells(std::size_t cell, double radius, std::vector<std::uint32_t>& cells) const {
    cells.clear();
    ForEachNeighbourCell(cell_keys_[cell], radius, [&](std::uint32_t neighbour) { cells.push_back(neighbour); });
}

int PointGrid::FindNearest(const Eigen::Vector3d& query, double max_distance) const {
    int best = -1;
    double best_squared = max_distance * max_distance;
    ForEachNeighbourSlot(VoxelOf(query, cell_size_), max_distance, [&](std::size_t slot) {
        const double squared = (sorted_points_[slot] - query).squaredNorm();
        if (squared <= best_squared) {
            best_squared = squared;
            best = index_[slot];
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
