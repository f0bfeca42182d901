#pragma once
/// A drifting odometry prior from ground truth: per-step relative motions corrupted by a
/// speed-scale bias, a yaw-rate bias that itself random-walks, and white noise.
#include <cstdint>

#include "core/trajectory.hpp"

namespace revisit {

struct OdometryNoiseConfig {
    bool enabled = true;
    double speed_scale_bias = 0.01;       ///< relative error of travelled distance (1%)
    double yaw_rate_bias = 0.002;         ///< [rad/s] initial gyro bias
    double yaw_bias_random_walk = 0.0005; ///< [rad/s/sqrt(s)] drift of that bias
    double translation_noise = 0.01;      ///< [m] white noise per step (per axis)
    double rotation_noise = 0.001;        ///< [rad] white noise per step (per axis)
};

/// T_odom_sensor per pose; the first equals the first ground-truth pose.
Poses SimulateOdometry(const Trajectory& ground_truth, const OdometryNoiseConfig& config, std::uint64_t seed);

}  // namespace revisit
