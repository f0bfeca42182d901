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
    explicit GlobalMapBuilder(double voxel_size);  ///< [m]; throws ConfigError unless > 0

    /// Adds a local map's points (in its node frame; Vector3f or Vector3d) at T_world_node.
    /// The first point to reach a voxel keeps it.
    template <typename Point>
    void Add(const std::vector<Point>& points_in_node, const Eigen::Isometry3d& T_world_node) {
        for (const auto& point : points_in_node) Insert(T_world_node * point.template cast<double>());
    }

    /// The map's points in the world frame, in insertion order (in single precision, as written).
    const std::vector<Eigen::Vector3f>& Points() const { return points_; }
    std::size_t size() const { return points_.size(); }

  private:
    void Insert(const Eigen::Vector3d& point_in_world);

    double voxel_size_;
    /// Open addressing, filled up to 90%: the demo's 0.7 M voxels take 17 MB (a node set: 41 MB).
    /// Building the map is the chain's peak of memory (issue 19).
    tsl::robin_set<Voxel, MixedVoxelHash> occupied_;
    std::vector<Eigen::Vector3f> points_;
};

}  // namespace revisit
