#pragma once
/// What a 2D laser's local map observed, and whether two maps contradict each other there
/// (docs/method.md, "2D loop-closure verification").
///
/// Why: the refinement's overlap coefficient counts the shared voxels against the smaller map's whole
/// extent. In a building, a revisit often crosses or runs along a corridor the other map walked, so
/// true pairs share 0.16-0.38 of the smaller map (orebro, reference poses) while a pair slid one door
/// spacing along a corridor shares as much. What tells them apart is where each map saw through: a
/// wall of one map placed where the other map's beams passed freely is a contradiction. Counted over
/// the region both maps observed, a true alignment agrees almost everywhere (0.88-0.97 of the walls
/// on orebro's pairs) whatever the share of the extent, and a wrong one puts walls in the other
/// map's free space.
#include <cstddef>
#include <cstdint>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace revisit {

/// A 2D map's cells in its own frame: occupied (a return fell there), free (a beam passed through it
/// and no return fell there), or unknown. Two bits per cell over the box of the scans' origins and returns.
class ObservedGrid {
  public:
    ObservedGrid() = default;
    /// `scans`: each scan's returns in its sensor frame (x, y; z ignored) and `T_map_scan` its pose in
    /// the map frame. A beam's last `hit_margin` [m] before its return are not marked free (range noise).
    ObservedGrid(const std::vector<std::vector<Eigen::Vector3f>>& scans, const std::vector<Eigen::Isometry3d>& T_map_scan,
                 double cell_size, double hit_margin);

    bool empty() const { return occupied_cells_.empty(); }
    double cell_size() const { return cell_; }
    bool Occupied(const Eigen::Vector2i& cell) const { return Get(occupied_, cell); }
    bool Free(const Eigen::Vector2i& cell) const { return Get(free_, cell); }
    /// The cell holding `point_in_map` [m].
    Eigen::Vector2i CellOf(const Eigen::Vector2d& point_in_map) const;
    /// [m] Centres of the occupied cells, in the map frame, in a fixed order.
    const std::vector<Eigen::Vector2d>& occupied_centres() const { return occupied_cells_; }
    std::size_t bytes() const { return (occupied_.capacity() + free_.capacity()) / 8 + occupied_cells_.capacity() * sizeof(Eigen::Vector2d); }

  private:
    bool Get(const std::vector<bool>& bits, const Eigen::Vector2i& cell) const;
    void Set(std::vector<bool>& bits, const Eigen::Vector2i& cell);
    double cell_ = 0.0;
    Eigen::Vector2i min_ = Eigen::Vector2i::Zero();  ///< the box's first cell
    int width_ = 0;
    int height_ = 0;
    std::vector<bool> occupied_;
    std::vector<bool> free_;
    std::vector<Eigen::Vector2d> occupied_cells_;
};

/// How the occupied cells of `b`, placed in `a` by `T_a_b`, fall among `a`'s cells.
struct FreeSpaceAgreement {
    int agree = 0;       ///< within one cell of an occupied cell of `a`
    int contradict = 0;  ///< in `a`'s free space
    /// agree / (agree + contradict); 0 when `a` observed none of `b`'s walls.
    double ratio() const { return agree + contradict > 0 ? double(agree) / double(agree + contradict) : 0.0; }
    int observed() const { return agree + contradict; }
};
FreeSpaceAgreement Agreement(const ObservedGrid& a, const ObservedGrid& b, const Eigen::Isometry3d& T_a_b);

}  // namespace revisit
