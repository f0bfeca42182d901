#pragma once
/// The odometry's local map: a voxel hash map with a bounded number of points per voxel
/// (METHOD.md section 1). Points of a voxel are stored contiguously for cache-friendly search.
#include <Eigen/Core>
#include <array>
#include <limits>
#include <cstdint>
#include <functional>
#include <tsl/robin_map.h>
#include <vector>

#include "core/voxel.hpp"
#include "odometry/shard_groups.hpp"

namespace revisit {

class VoxelHashMap {
  public:
    /// `voxel_size` [m]; a voxel holds at most `max_points_per_voxel` points, at least
    /// voxel_size / sqrt(max_points_per_voxel) apart (METHOD.md section 1). Memory: every voxel
    /// reserves max_points_per_voxel points (24 bytes each), so keep that number small.
    VoxelHashMap(double voxel_size, int max_points_per_voxel);

    /// Adds world-frame points; order matters (the first points of a voxel are kept). Parallel, with
    /// the result of adding them one by one in order.
    void AddPoints(const std::vector<Eigen::Vector3d>& points);
    /// Drops voxels whose first point is farther than `max_distance` [m] from `origin`, and those no
    /// point fell in since the stamp `oldest_kept` (SetStamp).
    void RemoveFarFrom(const Eigen::Vector3d& origin, double max_distance,
                       double oldest_kept = -std::numeric_limits<double>::infinity());
    /// The stamp (e.g. the travel [m]) the points added next carry: a voxel keeps the stamp of the
    /// last point that fell in it, added or not (a voxel full of points still sees the scene).
    void SetStamp(double stamp) { stamp_ = stamp; }
    void Clear();

    /// Nearest map point to `query` within the 27 voxels around it and strictly closer than
    /// `max_distance` [m]; nullptr when there is none. Exact within those voxels: voxels that
    /// cannot beat the best point so far are not even looked up. The pointer is valid until the
    /// map changes.
    const Eigen::Vector3d* FindNearest(const Eigen::Vector3d& query, double max_distance) const;

    /// The slots of the 27 voxels around one query voxel, kept between ICP iterations (issue 19): while
    /// a point stays in the same voxel, its neighbours are not looked up again. Valid while the map
    /// does not change; reset it (a default one) before each registration.
    ///
    /// It also keeps the last search's answer: where it was asked, the nearest point's distance and a
    /// lower bound on every other point's. A query that moved by d from there, within the same voxel,
    /// has the same unique nearest point while nearest + d < other - d and nearest + d < max_distance
    /// (triangle inequality), so it is answered without a search: ICP's late iterations move points by
    /// millimetres, far less than the gaps between map points. Likewise a query that found nothing
    /// within max_distance, every point being at least other away, finds nothing while other - d >=
    /// max_distance (points of new geometry, ~30% of the searches on a simulated city turn).
    struct Neighbourhood {
        static constexpr std::int32_t kUnknown = -2;  ///< not looked up yet
        Voxel centre = Voxel::Constant(std::numeric_limits<int>::min());
        std::array<std::int32_t, 27> slots{};  ///< per neighbour offset, -1: no such voxel
        Eigen::Vector3d searched_at = Eigen::Vector3d::Zero();  ///< query of the last search
        const Eigen::Vector3d* nearest = nullptr;               ///< its answer (nullptr: none within max_distance)
        double nearest_distance = 0.0;                          ///< [m] from searched_at to *nearest
        double other_distance = 0.0;  ///< [m] no other point of the 27 voxels is closer to searched_at (no point at all when nearest is nullptr)
        double max_distance = 0.0;    ///< [m] of the last search (0: none yet, reuse nothing)
    };
    /// FindNearest with `cache` for this query's neighbourhood: the same result, fewer hash lookups
    /// and searches.
    const Eigen::Vector3d* FindNearest(const Eigen::Vector3d& query, double max_distance, Neighbourhood& cache) const;

    /// Keep a plane normal per voxel (point-to-plane ICP): after each AddPoints, the voxels whose
    /// points changed get their normal recomputed from their own points; the others keep theirs.
    /// `in_plane`: a 2D laser's map (every point at one height): the normals are those of the lines the
    /// points lie along, within the plane.
    void EnableNormals(bool enabled, bool in_plane = false) {
        normals_enabled_ = enabled;
        normals_in_plane_ = in_plane;
        if (!enabled) {
            normals_.clear();
            normal_ok_.clear();
            normal_counts_.clear();
        }
    }
    /// The unit normal of the voxel holding `point` (a pointer FindNearest returned), or nullptr when
    /// its points do not span a plane (too few, collinear, or a volume): the caller falls back to
    /// point-to-point. Valid until the map changes.
    const Eigen::Vector3d* NormalOf(const Eigen::Vector3d* point) const {
        const std::size_t slot = static_cast<std::size_t>(point - points_.data()) / max_points_;
        return slot < normal_ok_.size() && normal_ok_[slot] ? &normals_[slot] : nullptr;
    }

    bool Empty() const { return voxels_.empty(); }
    std::size_t NumVoxels() const { return voxels_.size(); }
    std::size_t NumPoints() const;
    std::vector<Eigen::Vector3d> Points() const;
    /// Appends the first point of every voxel within `radius` [m] of `origin` (one per voxel: a
    /// picture of the map at its voxel's resolution).
    void PointsNear(const Eigen::Vector3d& origin, double radius, std::vector<Eigen::Vector3d>& out) const;
    /// Appends every point of every voxel within `radius` [m] of `origin` (a picture of the map finer
    /// than its voxels).
    void AllPointsNear(const Eigen::Vector3d& origin, double radius, std::vector<Eigen::Vector3d>& out) const;
    double voxel_size() const { return voxel_size_; }

  private:
    /// FindNearest over the neighbour voxels `slot_of(centre, k)` gives (-1: none), k in visiting order.
    /// `other2`, when given, gets a lower bound on the squared distance [m^2] of every point of the
    /// 27 voxels other than the one returned (infinity when there is none).
    template <typename SlotOf>
    const Eigen::Vector3d* Search(const Eigen::Vector3d& query, double max_distance, const SlotOf& slot_of,
                                  double* other2 = nullptr) const;
    /// One point, as the serial definition adds it (a new voxel gets the next slot).
    void AddPoint(const Eigen::Vector3d& point);
    void AddPoint(const Eigen::Vector3d& point, const Voxel& voxel);
    /// Adds `point` to the voxel in `slot` unless it is full or the point is too close to one of its points.
    bool TryAddToSlot(std::size_t slot, const Eigen::Vector3d& point);
    /// Recomputes the normal of every voxel whose point count changed since its last computation.
    void UpdateNormals();

    double voxel_size_;
    double inv_voxel_size_;
    int max_points_;
    double min_spacing2_;  ///< [m^2] squared minimum distance between points of one voxel
    tsl::robin_map<Voxel, std::uint32_t, VoxelHash> index_;  ///< voxel -> slot
    std::vector<Voxel> voxels_;                              ///< slot -> voxel
    std::vector<std::uint16_t> counts_;                      ///< slot -> number of points
    std::vector<double> seen_;                               ///< slot -> stamp of the last point that fell in it
    double stamp_ = 0.0;
    std::vector<Eigen::Vector3d> points_;                    ///< slot * max_points_ + k
    bool normals_enabled_ = false;
    bool normals_in_plane_ = false;
    std::vector<Eigen::Vector3d> normals_;       ///< slot -> unit plane normal (when normal_ok_)
    std::vector<std::uint8_t> normal_ok_;        ///< slot -> the voxel's points span a plane
    std::vector<std::uint16_t> normal_counts_;   ///< slot -> point count the normal was computed from
    // Buffers of AddPoints and RemoveFarFrom, kept between frames (no allocation per frame).
    std::vector<Voxel> point_voxels_;
    std::vector<std::uint32_t> point_shards_;
    ShardGroups shard_groups_;
    std::vector<std::uint8_t> pending_;  ///< the point's voxel was not in the map
    std::vector<std::uint8_t> far_;      ///< per slot
};

}  // namespace revisit
