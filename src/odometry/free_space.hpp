#pragma once
/// Where a 2D laser's beams have passed: the cells between the sensor and each return. A pose that
/// puts a scan's returns in space earlier beams crossed, or its beams through mapped walls, contradicts
/// what the laser saw; a correlative match's score counts only returns that land on walls, so two
/// poses that explain the same share of a scan are told apart by what their beams cross (the aliases
/// of a corridor or of a room turned by 90 deg).
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <tsl/robin_set.h>
#include <vector>

#include "odometry/voxel_hash_map.hpp"

namespace revisit {

/// Two counts of points, `a` clearly above `b`: by more than three standard deviations of their
/// difference (each count about Poisson: two differ by sqrt(a + b) by chance).
inline bool ClearlyMore(double a, double b) { return a - b > 3.0 * std::sqrt(a + b); }

class FreeSpace2D {
  public:
    explicit FreeSpace2D(double cell) : cell_(cell) {}

    /// The cells each beam from `origin` to a return in `returns_in_world` crosses, short of its last
    /// `margin` [m] (the return's own wall, and the range noise).
    void AddBeams(const Eigen::Vector3d& origin, const std::vector<Eigen::Vector3d>& returns_in_world, double margin);
    /// Forgets the cells farther than `radius` [m] from `origin` (the odometry's map radius) once the
    /// cells have doubled since the last time: the sweep costs as much as the set holds, and a frame adds
    /// a few hundred cells. The set stays within twice the map's disc.
    void RemoveFarFrom(const Eigen::Vector3d& origin, double radius);
    bool Free(const Eigen::Vector3d& point) const { return cells_.count(Key(point)) != 0; }
    std::size_t NumCells() const { return cells_.size(); }
    double cell() const { return cell_; }

  private:
    std::uint64_t Key(const Eigen::Vector3d& point) const;
    /// The cell key's bits mixed (splitmix64's finalizer): std::hash of an integer is the integer, and
    /// the set's power-of-two buckets would see the y bits alone.
    struct CellHash {
        std::size_t operator()(std::uint64_t key) const {
            key = (key ^ (key >> 30)) * 0xbf58476d1ce4e5b9ULL;
            key = (key ^ (key >> 27)) * 0x94d049bb133111ebULL;
            return static_cast<std::size_t>(key ^ (key >> 31));
        }
    };
    double cell_;
    std::size_t kept_ = 0;  ///< cells after the last sweep
    tsl::robin_set<std::uint64_t, CellHash> cells_;
};

/// What a scan placed at `T_world_sensor` contradicts.
struct BeamConflicts {
    std::size_t returns_in_free = 0;     ///< returns in a crossed cell with no map point within a cell
    std::size_t beams_through_walls = 0; ///< beams that cross a map point short of their last `margin`
    std::size_t Total() const { return returns_in_free + beams_through_walls; }
};

/// The conflicts of `points_in_sensor` (returns, the sensor at the origin) at `T_world_sensor` with the
/// beams `free` holds and the walls `map` holds; `margin` [m] as in AddBeams.
BeamConflicts CountBeamConflicts(const FreeSpace2D& free, const VoxelHashMap& map, const std::vector<Eigen::Vector3d>& points_in_sensor,
                                 const Eigen::Isometry3d& T_world_sensor, double margin);

}  // namespace revisit
