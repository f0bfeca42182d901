#include "optimization/free_space.hpp"

#include <algorithm>
#include <cmath>

namespace revisit {
namespace {

Eigen::Vector2i Floor(const Eigen::Vector2d& p, double cell) {
    return {static_cast<int>(std::floor(p.x() / cell)), static_cast<int>(std::floor(p.y() / cell))};
}

}  // namespace

ObservedGrid::ObservedGrid(const std::vector<std::vector<Eigen::Vector3f>>& scans, const std::vector<Eigen::Isometry3d>& T_map_scan,
                           double cell_size, double hit_margin)
    : cell_(cell_size) {
    const std::size_t n = std::min(scans.size(), T_map_scan.size());
    // Each scan's origin and returns in the map frame, once: the box, the beams and the returns use them.
    std::vector<Eigen::Vector2d> origins(n);
    std::vector<std::vector<Eigen::Vector2d>> hits(n);
    Eigen::Vector2i lo(INT32_MAX, INT32_MAX), hi(INT32_MIN, INT32_MIN);
    const auto grow = [&](const Eigen::Vector2d& p) {
        const Eigen::Vector2i c = Floor(p, cell_);
        lo = lo.cwiseMin(c);
        hi = hi.cwiseMax(c);
    };
    for (std::size_t s = 0; s < n; ++s) {
        origins[s] = T_map_scan[s].translation().head<2>();
        grow(origins[s]);
        hits[s].reserve(scans[s].size());
        for (const auto& p : scans[s]) {
            hits[s].push_back((T_map_scan[s] * p.cast<double>()).head<2>());
            grow(hits[s].back());
        }
    }
    if (lo.x() > hi.x()) return;
    min_ = lo;
    width_ = hi.x() - lo.x() + 1;
    height_ = hi.y() - lo.y() + 1;
    occupied_.assign(std::size_t(width_) * std::size_t(height_), false);
    free_.assign(occupied_.size(), false);
    // Beams first, returns after: a cell that held a return in any scan is occupied, not free.
    const double step = 0.5 * cell_;
    for (std::size_t s = 0; s < n; ++s) {
        for (const auto& hit : hits[s]) {
            const double length = (hit - origins[s]).norm() - hit_margin;
            if (length <= 0.0) continue;
            const Eigen::Vector2d direction = (hit - origins[s]).normalized();
            // Half-cell steps visit every cell the beam crosses but for corner clips, which only thin the
            // free space (the check then counts fewer contradictions, never more).
            for (double t = 0.0; t < length; t += step) Set(free_, Floor(origins[s] + t * direction, cell_));
        }
    }
    for (const auto& scan_hits : hits) {
        for (const auto& hit : scan_hits) {
            const Eigen::Vector2i c = Floor(hit, cell_);
            if (Get(occupied_, c)) continue;
            Set(occupied_, c);
            occupied_cells_.push_back((c.cast<double>() + Eigen::Vector2d(0.5, 0.5)) * cell_);
        }
    }
    for (std::size_t i = 0; i < free_.size(); ++i)
        if (occupied_[i]) free_[i] = false;
}

Eigen::Vector2i ObservedGrid::CellOf(const Eigen::Vector2d& point_in_map) const { return Floor(point_in_map, cell_); }

bool ObservedGrid::Get(const std::vector<bool>& bits, const Eigen::Vector2i& cell) const {
    const Eigen::Vector2i local = cell - min_;
    if (local.x() < 0 || local.y() < 0 || local.x() >= width_ || local.y() >= height_) return false;
    return bits[std::size_t(local.y()) * std::size_t(width_) + std::size_t(local.x())];
}

void ObservedGrid::Set(std::vector<bool>& bits, const Eigen::Vector2i& cell) {
    const Eigen::Vector2i local = cell - min_;
    if (local.x() < 0 || local.y() < 0 || local.x() >= width_ || local.y() >= height_) return;
    bits[std::size_t(local.y()) * std::size_t(width_) + std::size_t(local.x())] = true;
}

FreeSpaceAgreement Agreement(const ObservedGrid& a, const ObservedGrid& b, const Eigen::Isometry3d& T_a_b) {
    FreeSpaceAgreement result;
    if (a.empty() || b.empty()) return result;
    for (const auto& centre : b.occupied_centres()) {
        const Eigen::Vector2d in_a = (T_a_b * Eigen::Vector3d(centre.x(), centre.y(), 0.0)).head<2>();
        const Eigen::Vector2i c = a.CellOf(in_a);
        // One cell of tolerance: the two maps' cells are not aligned, and a wall on a cell boundary
        // falls on either side.
        bool near = false;
        for (int dy = -1; dy <= 1 && !near; ++dy)
            for (int dx = -1; dx <= 1 && !near; ++dx) near = a.Occupied(c + Eigen::Vector2i(dx, dy));
        if (near) {
            ++result.agree;
        } else if (a.Free(c)) {
            ++result.contradict;
        }
    }
    return result;
}

}  // namespace revisit
