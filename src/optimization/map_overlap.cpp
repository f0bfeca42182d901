#include "optimization/map_overlap.hpp"

#include <algorithm>
#include <cmath>
#include <tsl/robin_map.h>
#include <tsl/robin_set.h>

#include "core/voxel.hpp"

namespace revisit {
namespace {

/// A ground cell as a voxel at height 0, hashed with MixedVoxelHash: robin tables bucket by the low
/// bits (a plain integer key left them to one coordinate and made the table grow without end).
using Cell = Voxel;

Cell CellOf(double x, double y, double inv_cell) {
    return Cell(int(std::floor(x * inv_cell)), int(std::floor(y * inv_cell)), 0);
}

}  // namespace

std::vector<Eigen::Vector2d> MapFootprint(const std::vector<Eigen::Vector3f>& points_in_map, double cell_size) {
    const double inv_cell = 1.0 / cell_size;
    tsl::robin_set<Cell, MixedVoxelHash> seen;
    std::vector<Eigen::Vector2d> centres;
    for (const auto& p : points_in_map) {
        if (!p.allFinite()) continue;
        const Cell cell = CellOf(p.x(), p.y(), inv_cell);
        if (!seen.insert(cell).second) continue;
        centres.emplace_back((cell.x() + 0.5) * cell_size, (cell.y() + 0.5) * cell_size);  // first-seen order: deterministic
    }
    return centres;
}

std::vector<PredictedOverlap> PredictOverlaps(const std::vector<std::vector<Eigen::Vector2d>>& footprints,
                                              const Poses& T_world_map, double cell_size, double min_overlap,
                                              int max_per_query, const std::function<bool(int, int)>& skip) {
    const double inv_cell = 1.0 / cell_size;
    const std::size_t n = std::min(footprints.size(), T_world_map.size());
    // Each map's footprint in the world (a moved cell centre lands in one cell; two centres may share one).
    std::vector<std::vector<Cell>> world(n);
    tsl::robin_map<Cell, std::vector<int>, MixedVoxelHash> maps_of_cell;
    for (std::size_t m = 0; m < n; ++m) {
        const Eigen::Isometry3d& T = T_world_map[m];
        tsl::robin_set<Cell, MixedVoxelHash> cells;
        for (const auto& c : footprints[m]) {
            const Eigen::Vector3d w = T * Eigen::Vector3d(c.x(), c.y(), 0.0);
            if (!w.allFinite()) continue;
            const Cell cell = CellOf(w.x(), w.y(), inv_cell);
            if (cells.insert(cell).second) world[m].push_back(cell);
        }
        for (const Cell& cell : world[m]) maps_of_cell[cell].push_back(int(m));  // ascending map ids per cell
    }
    std::vector<PredictedOverlap> pairs;
    std::vector<int> shared(n, 0);
    for (std::size_t q = 1; q < n; ++q) {
        std::fill(shared.begin(), shared.begin() + std::ptrdiff_t(q), 0);
        for (const Cell& cell : world[q]) {
            for (const int r : maps_of_cell.at(cell)) {
                if (r >= int(q)) break;
                ++shared[std::size_t(r)];
            }
        }
        std::vector<PredictedOverlap> candidates;
        for (std::size_t r = 0; r < q; ++r) {
            if (shared[r] == 0 || skip(int(q), int(r))) continue;
            const auto smaller = std::min(world[q].size(), world[r].size());
            const double overlap = double(shared[r]) / double(smaller);
            if (overlap >= min_overlap) candidates.push_back({int(q), int(r), overlap});
        }
        std::stable_sort(candidates.begin(), candidates.end(),
                         [](const PredictedOverlap& a, const PredictedOverlap& b) { return a.overlap > b.overlap; });
        if (int(candidates.size()) > max_per_query) candidates.resize(std::size_t(std::max(0, max_per_query)));
        pairs.insert(pairs.end(), candidates.begin(), candidates.end());
    }
    return pairs;
}

}  // namespace revisit
