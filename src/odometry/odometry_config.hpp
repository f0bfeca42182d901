#pragma once
/// Parameters of the KISS-ICP-class LiDAR odometry (METHOD.md section 1).
/// Defaults are the paper-era ones; "later" variants are options.
namespace revisit {

/// Geman-McClure kernel scale relative to the adaptive threshold sigma (METHOD.md section 1).
enum class IcpKernel {
    kPaper,  ///< k = sigma / 3 (paper-era code)
    kLater,  ///< k = sigma (later code)
};

/// What an ICP correspondence measures (METHOD.md section 1 names point-to-point, KISS-ICP's choice).
enum class IcpResidual {
    kPointToPoint,  ///< the full vector to the nearest map point (KISS-ICP)
    /// Its component along the normal of the nearest point's map voxel where that voxel's points span a
    /// plane, else point-to-point. Sparse rings on walls (16-beam sensors) otherwise pull in pitch. In
    /// planar mode (2D lasers) the voxel's line and its in-plane normal: point-to-line.
    kPointToPlane,
};

struct OdometryConfig {
    // Range and voxels.
    double max_range = 100.0;        ///< [m] points farther away are dropped; also the map radius
    double min_range = 5.0;          ///< [m] points closer are dropped (ego vehicle)
    double voxel_size = 0.0;         ///< [m] map voxel v; 0 means max_range / 100
    int max_points_per_voxel = 20;   ///< map points kept per voxel
    // Adaptive threshold (METHOD.md section 1).
    double initial_threshold = 2.0;  ///< [m] sigma before any motion was seen
    double min_motion_th = 0.1;      ///< [m] a frame updates sigma only when its model error exceeds this (KISS-ICP code)
    // ICP.
    /// Paper-era by default (METHOD.md). On the simulated demo city each kernel stalls once: sigma/3
    /// over the first ~100 scans from rest, sigma around scan 2886 (see the issue notes).
    IcpKernel kernel = IcpKernel::kPaper;
    IcpResidual residual = IcpResidual::kPointToPoint;  ///< settings from the data: point-to-plane for sparse rings
    int max_iterations = 500;        ///< Gauss-Newton iterations per frame
    double convergence = 1e-4;       ///< stop when |dx| of an update is below this [m, rad]
    /// Anderson acceleration of the ICP iterations over this many previous steps, an extrapolation kept
    /// only when the robust cost does not rise (0: plain Gauss-Newton iterations). Same stopping test.
    /// Off by default: 5-8% less odometry CPU, but it moves the poses (README, issue 19).
    int anderson_depth = 0;
    int min_correspondences = 20;    ///< fewer: the frame is degenerate, keep the prediction
    double max_correction = 20.0;    ///< [m] translation of prediction^-1 * ICP result beyond which ICP is deemed diverged
    /// A frame whose translation correction exceeds this many times the RMS correction of the earlier
    /// frames (at least one map voxel) jumped to a wrong minimum: it keeps the prediction. 0 = off.
    double max_correction_factor = 8.0;
    /// A registered frame needs this share of its points within one map voxel of the map; fewer: the
    /// scan does not show the mapped scene (sensor fault, garbage) and keeps the prediction. 0 = off.
    double min_agreement = 0.1;
    // Motion model and inputs.
    /// Also register from the translation-only prediction when the constant-velocity turn moves points by
    /// more than a voxel, keeping the better result (swaying handheld sensors; 2 ICPs on those frames;
    /// never with a wheel-odometry prior, which measures the turn).
    bool turn_hypothesis = true;
    /// 3D: register point-to-plane until the motion is measured. A spinning sensor's ground rings snap
    /// onto the last scan's under point-to-point at the start; patterns without rings do not need it.
    bool ring_start = true;
    /// Planar mode: start the ICP from a correlative scan match (odometry/correlative_matcher.hpp) over
    /// the windows below around the prediction: on every frame without a wheel-odometry prior (key
    /// frames of a laser logged alone are up to ~1 m and 30 deg apart, far outside ICP's basin), and
    /// with one on a frame whose ICP from the prior failed.
    bool correlative_start = true;
    double correlative_window = 1.5;               ///< [m] translations searched each way (x and y)
    double correlative_angular_window_deg = 45.0;  ///< [deg] rotations searched each way
    /// Without wheel odometry: the match also pulls towards the ray along the platform's heading (the
    /// chord of the turn): a pose one correlative_window off that ray loses 5% of the best score, the
    /// matcher's prior_weight. A wheeled platform drives forward; a corridor's aliases a door spacing
    /// back or sideways otherwise win on the ~1% their scores differ by (orebro, docs/method.md).
    bool correlative_heading_prior = true;
    /// [m] the map keeps only voxels a scan saw within this much travel (0: every voxel within range,
    /// KISS-ICP). An earlier pass of the same place lies in the map where the odometry's drift put it,
    /// and a scan that sees it again registers to that copy instead of to the scans just before.
    double map_travel_horizon = 0.0;
    /// Planar, without wheel odometry: a frame is also registered to the voxels seen within the last
    /// max_range of travel, and that pose replaces the whole map's when it explains the scan clearly
    /// better against them (a drifted earlier pass pulled the frame; odometry/recent_travel_check.cpp).
    bool recent_travel_check = true;
    /// Planar, without wheel odometry: the odometry keeps where its frames' beams passed, and a retry of
    /// the correlative match over twice the windows is kept only when it does not contradict those beams
    /// clearly more than the first match (returns in crossed space, beams through mapped walls;
    /// odometry/free_space.hpp).
    bool beam_check = true;
    bool deskew = false;             ///< constant-velocity motion compensation of each sweep
    bool azimuth_clockwise = true;   ///< deskew without point times: sweep direction (KITTI: clockwise, s = 0.5 (1 - atan2(y, x) / pi))
    bool planar = false;             ///< estimate only x, y, yaw (2D lasers: z, roll, pitch are unobservable)
    bool use_prior = true;           ///< use Scan::T_odom_sensor increments (wheel odometry) as the motion guess when present
    /// Remove the prior's rotation bias per metre, measured against the registration (odometry/prior_bias.hpp),
    /// once its blocks agree (a platform's steady bias): the radish maps' walls single (intel's inner
    /// corridors, fr079's bend). No effect without a prior.
    bool prior_bias_correction = true;
    double prior_bias_window = 50.0;  ///< [m] of travel per block of the bias estimate (odometry/prior_bias.hpp)
    /// KITTI's 0.205 degree vertical-angle correction is NOT done here: it is a property of the
    /// data, applied by the reader (ReaderOptions::kitti_vertical_correction, configs/kitti.yaml).
    double degenerate_thickness = 0.02;  ///< [m] a frame whose points lie within this of a plane (3D) or line (planar) is degenerate

    /// The map voxel size actually used [m].
    double VoxelSize() const { return voxel_size > 0.0 ? voxel_size : max_range / 100.0; }
};

/// `config` with the range crop `max_range` [m] and the same map voxels (a voxel size of 0 would
/// otherwise follow the range).
inline OdometryConfig WithMaxRange(OdometryConfig config, double max_range) {
    if (config.voxel_size == 0.0) config.voxel_size = config.VoxelSize();
    config.max_range = max_range;
    return config;
}

}  // namespace revisit
