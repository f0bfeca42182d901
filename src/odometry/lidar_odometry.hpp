#pragma once
/// KISS-ICP-class scan-to-map LiDAR odometry (METHOD.md section 1): feed scans in order,
/// get T_world_sensor of each (world = the first scan's sensor frame).
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <optional>
#include <string>
#include <vector>

#include "core/scan.hpp"
#include "core/trajectory.hpp"
#include "odometry/adaptive_threshold.hpp"
#include "odometry/free_space.hpp"
#include "odometry/odometry_config.hpp"
#include "odometry/preprocess.hpp"
#include "odometry/prior_bias.hpp"
#include "odometry/voxel_hash_map.hpp"

namespace revisit {

/// What happened to the last frame; `warning` is non-empty when the pose is only a prediction.
struct OdometryFrameStats {
    std::size_t input_points = 0;
    std::size_t cropped_points = 0;      ///< after the range crop
    std::size_t map_points = 0;          ///< after the 0.5 v downsampling (what enters the map)
    std::size_t source_points = 0;       ///< after the 1.5 v downsampling (what is registered)
    std::size_t correspondences = 0;     ///< in the last ICP iteration
    std::size_t plane_correspondences = 0;  ///< of those, point-to-plane ones (odometry.residual)
    bool planes_only = false;            ///< the point-to-plane correspondences were used alone
    double agreement = 0.0;              ///< share of the registered points within one voxel of the map
    int iterations = 0;
    double sigma = 0.0;                  ///< [m] adaptive threshold used for this frame
    bool prior_used = false;             ///< the prediction came from Scan::T_odom_sensor
    double prior_heading_bias = 0.0;     ///< [rad/m] the prior's estimated turn per metre about the sensor z, removed
    bool turn_hypothesis_used = false;   ///< the translation-only prediction registered better
    bool correlative_used = false;       ///< the ICP started from a correlative scan match
    double correlative_score = 0.0;      ///< its mean likelihood in [0, 1]
    bool recent_travel_used = false;     ///< registered to the recent travel's map, not the whole map (CheckRecentTravel)
    bool degenerate = false;             ///< pose = prediction, map not updated
    std::string warning;                 ///< why the frame was degenerate
};

class LidarOdometry {
  public:
    /// Throws ConfigError on impossible values (non-positive ranges, voxel size, ...).
    explicit LidarOdometry(const OdometryConfig& config = {});

    /// Registers the next scan and returns its pose T_world_sensor. Never returns a non-finite
    /// pose: a degenerate frame (empty, all out of range, a single plane, too few
    /// correspondences) gets the motion prediction and a warning in LastStats().
    Eigen::Isometry3d RegisterScan(const Scan& scan);
    /// RegisterScan with the scan's preparation done beforehand (PrepareScan, possibly on another thread
    /// while the scan before registered): the same pose. Prepared with settings other than the current
    /// ones (SetMaxRange since), the scan is prepared again here.
    Eigen::Isometry3d RegisterPrepared(const Scan& scan, PreparedScan prepared);

    const Poses& poses() const { return poses_; }
    /// The last scan's cropped (and, if enabled, deskewed) points, full resolution, sensor frame.
    const std::vector<Eigen::Vector3d>& LastDeskewedPoints() const { return deskewed_; }
    /// The last scan's points after the 0.5 v downsampling (sensor frame).
    const std::vector<Eigen::Vector3d>& LastDownsampledPoints() const { return downsampled_; }
    const OdometryFrameStats& LastStats() const { return stats_; }
    /// The local map with every registered frame in it.
    const VoxelHashMap& LocalMap();
    const OdometryConfig& config() const { return config_; }
    /// Changes the range crop (and the map radius, the adaptive threshold's lever arm) from the next
    /// scan on; the map's voxels stay. For a scene whose scale changes (pipeline/scene_scale_watch.hpp).
    /// Throws ConfigError unless min_range < max_range.
    void SetMaxRange(double max_range);
    /// Count of frames that only got the prediction.
    std::size_t NumDegenerateFrames() const { return num_degenerate_; }

  private:
    /// Motion expected from the previous pose to this scan: wheel odometry increment when
    /// enabled and available, else the last registered motion (constant velocity).
    Eigen::Isometry3d PredictMotion(const Scan& scan);
    /// Adds the last registered frame's points to the map and drops voxels beyond the range from it.
    void ApplyMapUpdate();
    /// Points too few or within `degenerate_thickness` of a plane (3D) or a line (planar).
    std::string DegeneracyReason(const std::vector<Eigen::Vector3d>& points) const;

    /// A 3D frame without a prior before kMotionsMeasuredAtStart measured motions (RegisterFrom).
    bool MotionUnmeasured() const;
    /// Source points within `radius` of a map point when placed at `T_world_sensor` (every `stride`-th
    /// point checked, the count scaled back).
    std::size_t CountAgreeing(const VoxelHashMap& map, const std::vector<Eigen::Vector3d>& source, const Eigen::Isometry3d& T_world_sensor, double radius,
                              std::size_t stride) const;
    /// The pose a correlative match of `source` against the map finds around the motion `delta` from
    /// `last_pose` (the prediction when there is nothing to match); `resolution` [m] gets its cell (0: none).
    Eigen::Isometry3d CorrelativeStart(const VoxelHashMap& map, const std::vector<Eigen::Vector3d>& source, const Eigen::Isometry3d& last_pose,
                                       const Eigen::Isometry3d& delta, double& resolution);
    /// ICP from `T_start` with the checks of a registration; empty and `T_new` set when it registered,
    /// else why not. `start_resolution` [m]: the start's known uncertainty (a correlative cell).
    std::string RegisterFrom(const VoxelHashMap& map, const std::vector<Eigen::Vector3d>& source, const Eigen::Isometry3d& T_start, const Eigen::Isometry3d& delta,
                             const Eigen::Isometry3d& last_pose, bool turn_hypothesis, double start_resolution, Eigen::Isometry3d& T_new);
    /// A frame registered to the whole map (`T_start` -> `T_new`) is registered again to the map of the
    /// last max_range of travel; when that map explains the scan clearly better at its own pose, the
    /// whole map's pull came from a drifted earlier pass, and the recent pose replaces it
    /// (odometry/recent_travel_check.cpp).
    void CheckRecentTravel(const std::vector<Eigen::Vector3d>& source, const Eigen::Isometry3d& last_pose, const Eigen::Isometry3d& delta,
                           Eigen::Isometry3d& T_start, Eigen::Isometry3d& T_new);
    /// [m] a translation correction beyond this is a jump, not a registration.
    double CorrectionLimit() const;

    OdometryConfig config_;
    VoxelHashMap map_;
    /// The voxels seen within the last max_range of travel (CheckRecentTravel), when recent_check_active_.
    VoxelHashMap recent_map_;
    bool recent_check_active_ = false;  ///< planar, no wheel odometry, odometry.recent_travel_check
    /// Where the frames' beams passed, for a 2D laser without wheel odometry (odometry.beam_check).
    std::optional<FreeSpace2D> free_space_;
    AdaptiveThreshold threshold_;
    Poses poses_;
    Eigen::Isometry3d last_delta_ = Eigen::Isometry3d::Identity();
    std::optional<Eigen::Isometry3d> last_T_odom_sensor_;
    PriorRotationBias prior_bias_;
    Eigen::Isometry3d raw_prior_delta_ = Eigen::Isometry3d::Identity();  ///< this frame's prior increment, uncorrected
    std::vector<Eigen::Vector3d> deskewed_;
    std::vector<Eigen::Vector3d> downsampled_;
    // Per-frame buffers kept between frames (issue 19: no allocation per scan).
    std::vector<Eigen::Vector3d> source_;           ///< registration points (1.5 v)
    std::vector<Eigen::Vector3d> points_in_world_;  ///< map points of the frame, world frame
    std::vector<Eigen::Vector3d> reference_;        ///< map points a correlative match rasterizes
    bool map_update_pending_ = false;               ///< points_in_world_ not yet in the map
    Eigen::Vector3d map_update_origin_ = Eigen::Vector3d::Zero();  ///< [m] the frame's position
    double map_update_radius_ = 0.0;                ///< [m] the range then
    double map_update_travel_ = 0.0;                ///< [m] the travel then
    double travel_ = 0.0;                           ///< [m] path length of the registered frames
    OdometryFrameStats stats_;
    std::size_t num_degenerate_ = 0;
    double sum_squared_corrections_ = 0.0;  ///< [m^2] translation corrections of registered frames
    std::size_t num_corrections_ = 0;
};

}  // namespace revisit
