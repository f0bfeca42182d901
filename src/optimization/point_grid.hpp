#pragma once
/// Nearest-neighbour search and voxel overlap on plain point clouds (voxel keys and
/// downsampling: core/voxel.hpp).
/// A hashed uniform grid, not a k-d tree:
/// ICP only ever asks for neighbours within a fixed radius, which a grid answers in O(1).
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <tsl/robin_map.h>
#include <vector>

#include "core/voxel.hpp"  // Voxel, VoxelHash, VoxelOf, VoxelDownsample

namespace revisit {

/// Overlap coefficient |A n B| / min(|A|, |B|) of the voxel sets of two clouds
/// given in the same frame (METHOD.md section 7 step 3); 0 when either is empty.
double VoxelOverlap(const std::vector<Eigen::Vector3d>& a, const std::vector<Eigen::Vector3d>& b, double voxel_size);

/// Points bucketed by a grid of cell edge `cell_size`; radius queries up to that edge.
/// Compact layout: the points are copied cell after cell (ascending index within a cell) with one
/// offset per cell, so a neighbourhood is a few contiguous runs and building costs no allocation per
/// cell. Every query visits cells in the same (dx, dy, dz) order and a cell's points by index, so the
/// answers do not depend on the layout.
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
        ForEachNeighbourSlot(VoxelOf(query, cell_size_), radius, [&](std::size_t slot) {
            if ((sorted_points_[slot] - query).squaredNorm() <= radius_squared) visit(index_[slot]);
        });
    }

    /// Occupied cells, numbered 0..num_cells()-1.
    std::size_t num_cells() const { return cell_keys_.size(); }
    /// Indices of the points of cell `cell`, ascending: slots [CellBegin, CellEnd) of `index()`.
    std::size_t CellBegin(std::size_t cell) const { return offsets_[cell]; }
    std::size_t CellEnd(std::size_t cell) const { return offsets_[cell + 1]; }
    /// The occupied cells within `radius` of cell `cell`, in the order every query visits them.
    void NeighbourCells(std::size_t cell, double radius, std::vector<std::uint32_t>& cells) const;
    /// The points in slot order, and each slot's index into the constructor's points.
    const std::vector<Eigen::Vector3d>& sorted_points() const { return sorted_points_; }
    const std::vector<int>& index() const { return index_; }

  private:
    int Reach(double radius) const { return std::max(1, static_cast<int>(std::ceil(radius / cell_size_))); }
    /// Calls visit(cell) for every occupied cell within `radius` of cell `center`, in (dx, dy, dz) order.
    template <typename Visit>
    void ForEachNeighbourCell(const Voxel& center, double radius, Visit&& visit) const {
        const int reach = Reach(radius);
        for (int dx = -reach; dx <= reach; ++dx) {
            for (int dy = -reach; dy <= reach; ++dy) {
                for (int dz = -reach; dz <= reach; ++dz) {
                    const Voxel key = center + Voxel(dx, dy, dz);
                    if (!MayBeOccupied(key)) continue;
                    const auto cell = cells_.find(key);
                    if (cell != cells_.end()) visit(cell->second);
                }
            }
        }
    }
    /// Visits every slot of the cells within `radius` of cell `center`.
    template <typename Visit>
    void ForEachNeighbourSlot(const Voxel& center, double radius, Visit&& visit) const {
        ForEachNeighbourCell(center, radius, [&](std::uint32_t cell) {
            for (std::size_t slot = offsets_[cell]; slot < offsets_[cell + 1]; ++slot) visit(slot);
        });
    }

    /// False only for a cell no point lies in: one bit per cell of the points' bounding box, so most
    /// empty neighbours cost a bit test instead of a hash lookup (a registration of two partly
    /// overlapping maps asks mostly about points far from the other map).
    bool MayBeOccupied(const Voxel& key) const {
        if (occupied_.empty()) return true;
        const Voxel offset = key - box_min_;
        if ((offset.array() < 0).any() || (offset.array() >= box_size_.array()).any()) return false;
        const std::size_t bit = BitOf(offset, box_size_);
        return (occupied_[bit >> 6] >> (bit & 63)) & 1u;
    }
    /// The bit of a cell at `offset` (>= 0, < size) from the lowest corner of a box of `size` cells.
    static std::size_t BitOf(const Voxel& offset, const Voxel& size) {
        return (std::size_t(offset.x()) * std::size_t(size.y()) + std::size_t(offset.y())) * std::size_t(size.z()) + std::size_t(offset.z());
    }

    double cell_size_;
    Voxel box_min_ = Voxel::Zero();
    Voxel box_size_ = Voxel::Zero();
    std::vector<std::uint64_t> occupied_;  ///< empty when the box is too large: every cell is looked up
    Voxel near_size_ = Voxel::Zero();      ///< the box grown by one cell each way
    std::vector<std::uint64_t> near_;      ///< bit: an occupied cell among the 27 around (with occupied_)
    std::vector<Eigen::Vector3d> sorted_points_;
    std::vector<int> index_;
    std::vector<std::size_t> offsets_;  ///< num_cells() + 1
    std::vector<Voxel> cell_keys_;
    tsl::robin_map<Voxel, std::uint32_t, VoxelHash> cells_;  // open addressing: ~2x faster lookups than std::unordered_map
};

}  // namespace revisit
