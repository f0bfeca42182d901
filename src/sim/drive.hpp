#pragma once
/// The vehicle (or handheld) motion along a planned path at the sensor rate.
#include <cstdint>
#include <vector>

#include "core/trajectory.hpp"
#include "sim/world.hpp"

namespace revisit {

struct MotionConfig {
    double rate = 10.0;                ///< [Hz] poses per second (PlanSimulation uses the sensor's rate)
    double cruise_speed = 10.0;        ///< [m/s]
    double max_lateral_accel = 2.0;    ///< [m/s^2] sets the speed in turns
    double max_accel = 1.5;            ///< [m/s^2]
    double max_decel = 2.5;            ///< [m/s^2]
    double start_speed = 3.0;          ///< [m/s]
    /// Car steering limits: the path is followed with curvature <= 1/min_turn_radius that changes
    /// gradually (clothoid-like blends), and the speed keeps the yaw rate and its change bounded.
    /// <= 0: the path is followed as given (walking, indoor robots).
    double min_turn_radius = 6.0;      ///< [m] real cars: >= 5-6 m
    double max_yaw_rate = 0.61;        ///< [rad/s] about 35 deg/s
    double max_yaw_accel = 0.35;       ///< [rad/s^2] about 20 deg/s^2: the yaw rate builds up over ~1 s
    double lookahead = 8.0;            ///< [m] look-ahead of the path follower (pure pursuit)
    double mount_height = 1.73;        ///< [m] sensor above the ground (KITTI Velodyne: 1.73)
    double mount_roll = 0.0;           ///< [rad]
    double mount_pitch = 0.0;          ///< [rad] positive tilts the sensor's x axis down
    double mount_yaw = 0.0;            ///< [rad]
    bool handheld = false;             ///< add walking sway and bob to the mount
    double sway_pitch = 0.14;          ///< [rad] amplitude (about 8 degrees)
    double sway_roll = 0.10;           ///< [rad] amplitude
    double sway_yaw = 0.08;            ///< [rad] amplitude
    double step_frequency = 1.8;       ///< [Hz] walking bob
    double bob_amplitude = 0.03;       ///< [m]
};

/// Sensor poses (T_world_sensor) and time stamps at `rate` along the path; the vehicle follows
/// the ground's slope (pitch and roll from its gradient). Sway phases come from `seed`.
Trajectory DrivePath(const std::vector<Eigen::Vector2d>& path, const Ground& ground, const MotionConfig& config,
                     std::uint64_t seed);

}  // namespace revisit
