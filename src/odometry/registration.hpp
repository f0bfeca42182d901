#pragma once
/// Scan-to-map ICP with a Geman-McClure kernel (METHOD.md section 1): point-to-point, or
/// point-to-plane where the nearest map point's voxel is planar.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstddef>
#include <vector>

#include "odometry/voxel_hash_map.hpp"

namespace revisit {

struct IcpParams {
    double max_correspondence_distance = 6.0;  ///< [m] 3 sigma of the adaptive threshold
    double kernel = 2.0 / 3.0;                 ///< [m] Geman-McClure scale k
    int max_iterations = 500;
    double convergence = 1e-4;                 ///< stop when |dx| < this [m, rad]
    int min_correspondences = 20;              ///< fewer: the registration is declared invalid
    bool planar = false;                       ///< solve only x, y, yaw (the other three stay as given)
    /// Where the nearest map point's voxel has a normal (VoxelHashMap::EnableNormals), the residual is
    /// its component along that normal; when those correspondences constrain every translation
    /// direction they are used alone, otherwise together with point-to-point ones for the rest.
    bool point_to_plane = false;
    /// Anderson acceleration over this many previous steps (0: plain Gauss-Newton iterations); an
    /// extrapolation is kept only when the robust cost does not rise (see RegisterPointsToMap).
    int anderson_depth = 0;
};

struct IcpResult {
    Eigen::Isometry3d T_world_sensor = Eigen::Isometry3d::Identity();  ///< the initial guess when !valid
    int iterations = 0;
    std::size_t correspondences = 0;  ///< in the last iteration
    std::size_t plane_correspondences = 0;  ///< point-to-plane ones in the last iteration
    bool planes_only = false;               ///< only point-to-plane correspondences were used
    bool converged = false;           ///< |dx| fell below the threshold
    bool valid = false;               ///< enough correspondences and a finite solution throughout
};

/// Aligns `points_in_sensor` to `map`, starting from `T_initial`. Each iteration finds every
/// point's nearest map point in the 27 voxels around it (rejected beyond the max distance),
/// takes the residual r (point-to-point, or n^T r with the voxel's normal n in point-to-plane mode,
/// where the planes alone are used when they constrain every translation direction),
/// weights it by k^2 / (k + |r|^2)^2 (Geman-McClure, METHOD.md section 1), solves the
/// 6x6 (planar: 3x3) Gauss-Newton system by LDLT and applies the update by the SE(3)
/// exponential; with `anderson_depth` the next iterate is extrapolated from the last steps (Anderson
/// acceleration), kept only when its truncated robust cost (each point without a correspondence
/// costs the kernel's ceiling) is no higher than the previous kept iterate's; the stopping test is
/// that of the plain step. The normal equations are summed with a deterministic reduction: the result is
/// bit-identical for any number of TBB threads.
IcpResult RegisterPointsToMap(const std::vector<Eigen::Vector3d>& points_in_sensor, const VoxelHashMap& map,
                              const Eigen::Isometry3d& T_initial, const IcpParams& params);

/// The closest pose with z = 0, roll = pitch = 0 (the planar mode's state space).
Eigen::Isometry3d ProjectToPlanar(const Eigen::Isometry3d& T);

}  // namespace revisit
