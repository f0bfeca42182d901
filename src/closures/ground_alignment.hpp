#pragma once
/// Levels a local map on its ground plane before projecting it (METHOD.md section 2, later code).
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <vector>

namespace revisit {

struct GroundAlignmentConfig {
    double cell_size = 1.0;        ///< [m] grid in which the lowest point of each cell is a ground candidate
    double inlier_distance = 0.3;  ///< [m] final gate of ground candidates to the plane
    double max_tilt_deg = 45.0;    ///< [deg] a fitted plane tilted more than this is rejected (identity kept)
    int min_ground_points = 20;    ///< fewer ground candidates: keep identity
    int iterations = 5;            ///< reweighting rounds; the gate shrinks from 4x to 1x inlier_distance
};

struct GroundAlignment {
    Eigen::Isometry3d T_ground_map = Eigen::Isometry3d::Identity();  ///< map frame -> levelled frame, ground at z = 0
    int num_ground_points = 0;                                       ///< inliers of the final fit (0: not aligned)
    bool aligned = false;
};

/// Fits the ground plane to the lowest point per cell (least squares on z, roll, pitch, solved in closed form
/// as the plane of least orthogonal distance), iteratively gated; returns the levelling transform (no yaw).
GroundAlignment AlignGround(const std::vector<Eigen::Vector3f>& points_in_map, const GroundAlignmentConfig& config = {});

}  // namespace revisit
