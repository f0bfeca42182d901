#pragma once
/// Nearest-neighbour search and voxel overlap on plain point clouds (voxel keys and
/// downsampling: core/voxel.hpp).
/// A hashed uniform grid stands in for a k-d tree (nanoflann is not a dependency):
/// ICP only ever asks for neighbours within a fixed radius, which a grid answers in O(1).
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <tsl/robin_map.h>
#include <vector>

#include "core/voxel.hpp"  // Voxel, VoxelHash, VoxelOf, VoxelDownsample

namespace revisit {

/// Overlap coefficient |A n B| / min(|A|, |B|) of the voxel sets of two clouds
/// given in the same frame (METHOD.md section 7 step 3); 0 when either is empty.
double VoxelOverlap(const std::vector<Eigen::Vector3d>& a, const std::vector<Eigen::Vector3d>& b, double voxel_size);

/// Points bucketed by a grid of cell edge `cell_size`; radius queries up to that edge.
class PointGrid {
  public:
    PointGrid(const std::vector<Eigen::Vector3d>& points, double cell_size);

    /// Index of the nearest point within `max_distance`, or -1. Fastest when
    /// `max_distance` <= cell size (27 cells); larger distances visit more cells.
    int FindNearest(const Eigen::Vector3d& query, double max_distance) const;
    /// Indices of all points within `radius` of `query`.
    std::vector<int> FindWithin(const Eigen::Vector3d& query, double radius) const;
    /// Calls visit(index) for every point within `radius` of `query`, without allocating.
    template <typename Visit>
    void ForEachWithin(const Eigen::Vector3d& query, double radius, Visit&& visit) const {
        const double radius_squared = radius * radius;
        ForEachNeighbour(query, radius, [&](int index) {
            if ((points_[index] - query).squaredNorm() <= radius_squared) visit(index);
        });
    }

    const std::vector<Eigen::Vector3d>& points() const { return points_; }

  private:
    /// Visits every point of the cells within `radius` of the query's cell.
    template <typename Visit>
    void ForEachNeighbour(const Eigen::Vector3d& query, double radius, Visit&& visit) const {
        const Voxel center = VoxelOf(query, cell_size_);
        const int reach = std::max(1, static_cast<int>(std::ceil(radius / cell_size_)));
        for (int dx = -reach; dx <= reach; ++dx) {
            for (int dy = -reach; dy <= reach; ++dy) {
                for (int dz = -reach; dz <= reach; ++dz) {
                    const auto cell = cells_.find(center + Voxel(dx, dy, dz));
                    if (cell == cells_.end()) continue;
                    for (const int index : cell->second) visit(index);
                }
            }
        }
    }

    std::vector<Eigen::Vector3d> points_;
    double cell_size_;
    tsl::robin_map<Voxel, std::vector<int>, VoxelHash> cells_;  // open addressing: ~2x faster lookups than std::unordered_map
};

}  // namespace revisit
