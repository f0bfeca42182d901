#pragma once
/// The corrected global map for viewing: local maps placed at their optimized node poses,
/// one point per voxel so that kilometres of driving stay a few million points.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <tsl/robin_set.h>
#include <vector>

#include "optimization/point_grid.hpp"

namespace revisit {

class GlobalMapBuilder {
  public:
    /// voxel_size [m] (throws ConfigError unless > 0). With max_points > 0, a map that would pass it
    /// doubles its voxel and thins the points kept so far to the new voxel (the first point to reach a
    /// voxel keeps it, as when built at that voxel from the start), until it fits: the map's size and
    /// the memory that builds it stay bounded however long the drive.
    explicit GlobalMapBuilder(double voxel_size, std::size_t max_points = 0);

    /// Adds a local map's points (in its node frame; Vector3f or Vector3d) at T_world_node.
    /// The first point to reach a voxel keeps it.
    template <typename Point>
    void Add(const std::vector<Point>& points_in_node, const Eigen::Isometry3d& T_world_node) {
        for (const auto& point : points_in_node) Insert(T_world_node * point.template cast<double>());
    }

    /// The map's points in the world frame, in insertion order (in single precision, as written).
    const std::vector<Eigen::Vector3f>& Points() const { return points_; }
    std::size_t size() const { return points_.size(); }
    double voxel_size() const { return voxel_size_; }  ///< [m] as given, or doubled to fit max_points

  private:
    void Insert(const Eigen::Vector3d& point_in_world);
    void Coarsen();

    double voxel_size_;
    std::size_t max_points_;
    /// Open addressing, filled up to 90%: the demo's 0.7 M voxels take 17 MB (a node set: 41 MB).
    /// Building the map is the chain's peak of memory.
    tsl::robin_set<Voxel, MixedVoxelHash> occupied_;
    std::vector<Eigen::Vector3f> points_;
};

}  // namespace revisit
