#include "optimization/point_grid.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <tsl/robin_set.h>

#include "core/error.hpp"

namespace revisit {
namespace {
void RequirePositive(double value, const char* name) {
    if (!(value > 0.0)) throw ConfigError(std::string(name) + " must be positive");
}
}  // namespace

double VoxelOverlap(const std::vector<Eigen::Vector3d>& a, const std::vector<Eigen::Vector3d>& b, double voxel_size) {
    RequirePositive(voxel_size, "voxel_size");
    tsl::robin_set<Voxel, VoxelHash> voxels_a;
    voxels_a.reserve(a.size() / 4);
    for (const auto& point : a) voxels_a.insert(VoxelOf(point, voxel_size));
    tsl::robin_set<Voxel, VoxelHash> voxels_b;
    voxels_b.reserve(b.size() / 4);
    for (const auto& point : b) voxels_b.insert(VoxelOf(point, voxel_size));
    if (voxels_a.empty() || voxels_b.empty()) return 0.0;
    const auto& smaller = voxels_a.size() <= voxels_b.size() ? voxels_a : voxels_b;
    const auto& larger = voxels_a.size() <= voxels_b.size() ? voxels_b : voxels_a;
    const auto common = std::count_if(smaller.begin(), smaller.end(), [&](const Voxel& key) {
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
    if (!cell_keys_.empty()) {
        Voxel low = cell_keys_.front(), high = cell_keys_.front();
        for (const Voxel& key : cell_keys_) {
            low = low.cwiseMin(key);
            high = high.cwiseMax(key);
        }
        const Eigen::Array3d size = (high - low).cast<double>().array() + 1.0;
        constexpr double kMaxBits = double(1u << 24);  // 2 MiB: beyond, plain lookups
        if (size.prod() <= kMaxBits) {
            box_min_ = low;
            box_size_ = (high - low).array() + 1;
            occupied_.assign(std::size_t(size.prod()) / 64 + 1, 0);
            for (const Voxel& key : cell_keys_) {
                const std::size_t bit = BitOf(key - box_min_, box_size_);
                occupied_[bit >> 6] |= std::uint64_t(1) << (bit & 63);
            }
            // The same box grown by a cell each way, a bit set where any of the 27 cells around is
            // occupied: a query whose own cell has none answers -1 from one bit (reach 1).
            near_size_ = box_size_.array() + 2;
            near_.assign(std::size_t(near_size_.cast<double>().prod()) / 64 + 1, 0);
            for (const Voxel& key : cell_keys_)
                for (int dx = 0; dx <= 2; ++dx)
                    for (int dy = 0; dy <= 2; ++dy) {
                        // Three cells along z are three consecutive bits (the word after gets the spill).
                        const std::size_t bit = BitOf(key - box_min_ + Voxel(dx, dy, 0), near_size_);
                        near_[bit >> 6] |= std::uint64_t(7) << (bit & 63);
                        if ((bit & 63) > 61) near_[(bit >> 6) + 1] |= std::uint64_t(7) >> (64 - (bit & 63));
                    }
        }
    }
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
    // The answer is the one a visit of the neighbour cells in (dx, dy, dz) order gives, keeping the
    // last of equally near points. Visiting the query's own cell first finds a near point at once;
    // then a cell whose box lies farther than it is skipped before its lookup, and a tie is decided by
    // the place the full visit gives each point (its cell's rank, then its slot), so ties come out the same.
    // The boxes are widened by a hair: a point's cell comes from a rounded division.
    const Voxel center = VoxelOf(query, cell_size_);
    const int reach = Reach(max_distance);
    const int side = 2 * reach + 1;
    const double margin = 1e-9 * (1.0 + query.cwiseAbs().maxCoeff());
    int best = -1;
    int best_rank = -1;
    double best_squared = max_distance * max_distance;
    const auto visit = [&](const Voxel& key, int rank) {
        if (!MayBeOccupied(key)) return;
        const auto cell = cells_.find(key);
        if (cell == cells_.end()) return;
        for (std::size_t slot = offsets_[cell->second]; slot < offsets_[cell->second + 1]; ++slot) {
            const double squared = (sorted_points_[slot] - query).squaredNorm();
            if (squared < best_squared || (squared == best_squared && rank >= best_rank)) {
                best_squared = squared;
                best = index_[slot];
                best_rank = rank;
            }
        }
    };
    if (reach == 1 && !near_.empty()) {
        const Voxel offset = center - box_min_ + Voxel::Ones();
        if ((offset.array() < 0).any() || (offset.array() >= near_size_.array()).any()) return -1;
        const std::size_t bit = BitOf(offset, near_size_);
        if (!((near_[bit >> 6] >> (bit & 63)) & 1u)) return -1;
    }
    const int own_rank = (reach * side + reach) * side + reach;
    visit(center, own_rank);
    const auto gap = [&](int key, int offset, double coordinate) {
        if (offset < 0) return std::max(0.0, coordinate - double(key + offset + 1) * cell_size_ - margin);
        if (offset > 0) return std::max(0.0, double(key + offset) * cell_size_ - coordinate - margin);
        return 0.0;
    };
    for (int dx = -reach; dx <= reach; ++dx) {
        const double gx = gap(center.x(), dx, query.x());
        for (int dy = -reach; dy <= reach; ++dy) {
            const double gy = gap(center.y(), dy, query.y());
            for (int dz = -reach; dz <= reach; ++dz) {
                const int rank = ((dx + reach) * side + dy + reach) * side + dz + reach;
                if (rank == own_rank) continue;
                const double gz = gap(center.z(), dz, query.z());
                if (gx * gx + gy * gy + gz * gz > best_squared) continue;
                visit(center + Voxel(dx, dy, dz), rank);
            }
        }
    }
    return best;
}

std::vector<int> PointGrid::FindWithin(const Eigen::Vector3d& query, double radius) const {
    std::vector<int> found;
    ForEachWithin(query, radius, [&](int index) { found.push_back(index); });
    return found;
}

}  // namespace revisit
