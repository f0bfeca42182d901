#pragma once
/// The corrected global map for viewing: local maps placed at their optimized node poses,
/// one point per voxel so that kilometres of driving stay a few million points.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <unordered_set>
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

    /// The map's points in the world frame, in insertion order.
    const std::vector<Eigen::Vector3d>& Points() const { return points_; }
    std::size_t size() const { return points_.size(); }

  private:
    void Insert(const Eigen::Vector3d& point_in_world);

    double voxel_size_;
    std::unordered_set<Eigen::Vector3i, VoxelHash> occupied_;
    std::vector<Eigen::Vector3d> points_;
};

}  // namespace revisit
