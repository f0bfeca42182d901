#pragma once
/// The corrected global map for viewing: local maps placed at their optimized node poses,
/// one point per voxel so that kilometres of driving stay a few million points.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <tsl/robin_set.h>
#include <vector>

#include "core/voxel.hpp"

namespace revisit {

class GlobalMapBuilder {
  public:
    /// voxel_size [m] (throws ConfigError unless > 0). With max_points > 0, a map that would pass it
    /// doubles its voxel and thins the points kept so far to the new voxel (the first point to reach a
    /// voxel keeps it, as when built at that voxel from the start), until it fits: the map's size and
    /// the memory that builds it stay bounded however long the drive.
    explicit GlobalMapBuilder(double voxel_size, std::size_t max_points = 0);

    /// Adds a local map's points (in its node frame; Vector3f or Vector3d) at T_world_node.
    /// The first point to reach a voxel keeps it (the voxel of the point in single precision, as written).
    template <typename Point>
    void Add(const std::vector<Point>& points_in_node, const Eigen::Isometry3d& T_world_node) {
        std::vector<Eigen::Vector3f> points_in_world;
        std::vector<Voxel> voxels;
        points_in_world.reserve(points_in_node.size());
        voxels.reserve(points_in_node.size());
        for (const auto& point : points_in_node) {
            // The voxel of the point as written: the one a coarser voxel's thinning sees again.
            points_in_world.push_back((T_world_node * point.template cast<double>()).template cast<float>());
            voxels.push_back(VoxelOf(points_in_world.back().template cast<double>(), voxel_size_));
        }
        AddBatch(points_in_world, voxels);
    }

    /// The map's points in the world frame, in insertion order (in single precision, as written).
    const std::vector<Eigen::Vector3f>& Points() const { return points_; }
    std::size_t size() const { return points_.size(); }
    double voxel_size() const { return voxel_size_; }  ///< [m] as given, or doubled to fit max_points

  private:
    void ReserveForCap();
    /// Adds one map's points (world frame) with their voxels at the current voxel size.
    void AddBatch(const std::vector<Eigen::Vector3f>& points_in_world, const std::vector<Voxel>& voxels);
    void Coarsen();

    double voxel_size_;
    std::size_t max_points_;
    /// The occupied voxels, sorted (12 bytes each). Building the map is the chain's peak of memory: a
    /// hash set took 16 bytes a bucket at most 90% full, and twice that while it grew (2 million
    /// voxels: up to 96 MB, against 24 MB here and one map's voxels merged in).
    std::vector<Voxel> occupied_;
    std::vector<Eigen::Vector3f> points_;
    /// Scratch of AddBatch, kept for its buckets: the voxels the map being added reached so far. A
    /// map's own first points come from a hash set (sorting every point of each map cost twice the
    /// time); only the thinning, over up to the cap's points, sorts to stay small.
    tsl::robin_set<Voxel, MixedVoxelHash> batch_seen_;
};

}  // namespace revisit
