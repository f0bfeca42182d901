#pragma once
/// Trajectory accuracy as the `evo` tool defines it (APE, RPE) and the KITTI odometry benchmark's
/// segment errors (METHOD.md section 7, "Trajectory accuracy"). Poses are associated by index.
#include "core/trajectory.hpp"
#include "evaluation/statistics.hpp"

#include <vector>

namespace revisit {

/// The rigid transform T (no scale) minimizing sum |p_ref_i - T * p_est_i|^2 over positions
/// (Umeyama 1991, as evo's `align`, with_scale = false). Needs >= 3 non-collinear positions for a
/// unique rotation; with fewer, returns the translation-only fit.
Eigen::Isometry3d AlignUmeyama(const Poses& estimate, const Poses& reference);

struct PoseErrors {
    std::vector<double> translation;   ///< [m] per pose (APE) or per pair (RPE)
    std::vector<double> rotation_deg;  ///< [deg] rotation angle of the error pose
    ErrorStatistics translation_stats;
    ErrorStatistics rotation_deg_stats;
};

struct ApeResult {
    PoseErrors errors;
    Eigen::Isometry3d T_ref_est = Eigen::Isometry3d::Identity();  ///< the alignment applied to the estimate
};

/// APE: E_i = P_est_i^-1 * P_ref_i after aligning the estimate (`align` true: SE(3) Umeyama; false: none),
/// evo's APE.ape_base. Translation error = |t_est_i - t_ref_i| (evo translation_part), rotation = angle of
/// E_i (evo rotation_angle_deg). Throws ConfigError when the lengths differ.
ApeResult ComputeApe(const Poses& estimate, const Poses& reference, bool align = true);

/// RPE over index pairs (0, d), (d, 2d), ... as evo with delta = d frames, all_pairs = false:
/// E = (Q_i^-1 Q_j)^-1 (P_i^-1 P_j), Q reference, P estimate.
PoseErrors ComputeRpe(const Poses& estimate, const Poses& reference, std::size_t delta_frames = 1);

struct KittiSegmentConfig {
    std::vector<double> lengths = {100, 200, 300, 400, 500, 600, 700, 800};  ///< [m] segment lengths
    std::size_t step_frames = 10;  ///< first frames every 10 frames, as the KITTI devkit
};

struct KittiLengthError {
    double length = 0.0;             ///< [m]
    std::size_t num_segments = 0;
    double translation_percent = 0.0;       ///< mean translation error / length [%]
    double rotation_deg_per_100m = 0.0;     ///< mean rotation error / length [deg / 100 m]
};

struct KittiErrors {
    std::size_t num_segments = 0;           ///< 0 when the trajectory is shorter than every length
    double translation_percent = 0.0;       ///< over all segments of all lengths, as the devkit's average
    double rotation_deg_per_100m = 0.0;
    std::vector<KittiLengthError> per_length;
};

/// KITTI devkit (evaluate_odometry.cpp): segments start every step_frames frames; a segment of length
/// L ends at the first frame whose reference travel exceeds the start's by more than L;
/// error = (P_est_first^-1 P_est_last)^-1 (P_ref_first^-1 P_ref_last), divided by L.
KittiErrors ComputeKittiErrors(const Poses& estimate, const Poses& reference, const KittiSegmentConfig& config = {});

}  // namespace revisit
