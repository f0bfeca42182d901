#pragma once
/// How fast the platform moves at the start of a sequence: a walk and a drive see similar ranges
/// (a handheld Livox in a courtyard: median range 17 m; KITTI: 10 m) but move ten times apart in
/// speed, and a local map should span a similar stretch of time, not of distance (section "Settings
/// from the data" of the README). Streaming: feed the first scans as they arrive.
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "core/scan.hpp"
#include "odometry/lidar_odometry.hpp"

namespace revisit {

struct MotionProfile {
    double speed = 0.0;        ///< [m/s] 75th percentile of the per-scan speed (0: unknown)
    double travel = 0.0;       ///< [m] over the scans looked at
    double duration = 0.0;     ///< [s] time the scans span
    std::size_t scans = 0;
    std::string source;        ///< "odometry prior", "lidar odometry" or empty (unknown)
    /// [rad] 90th percentile of how far each step's rotation differs from the previous step's: the error
    /// of a constant-velocity turn prediction (a car's smooth turns: ~0.1 deg; a swaying hand: degrees).
    double turn_misprediction = 0.0;

    bool known() const { return speed > 0.0; }
    std::string Describe() const;
};

/// Measures the speed from the scans' odometry prior when they carry one, else by registering them
/// with the project's odometry. Stops after `max_scans` or `max_seconds` of data.
class MotionMeter {
  public:
    MotionMeter(const OdometryConfig& odometry, std::size_t max_scans = 150, double max_seconds = 60.0)
        : odometry_config_(odometry), max_scans_(max_scans), max_seconds_(max_seconds) {}

    /// Returns true while more scans are wanted.
    bool Add(const Scan& scan);
    bool Done() const;
    MotionProfile Profile() const;

  private:
    OdometryConfig odometry_config_;
    std::size_t max_scans_;
    double max_seconds_;
    std::optional<LidarOdometry> odometry_;
    std::vector<double> speeds_;  ///< [m/s] per scan step
    std::vector<double> turn_changes_;  ///< [rad] per pair of consecutive steps
    std::optional<Eigen::Isometry3d> last_step_;
    std::optional<Eigen::Isometry3d> last_pose_;
    double last_time_ = 0.0;
    double first_time_ = 0.0;
    double travel_ = 0.0;
    std::size_t scans_ = 0;
    bool from_prior_ = false;
};

}  // namespace revisit
