#pragma once
/// Routes through a street graph with a requested number of revisits, and the vehicle
/// (or handheld) motion along them at the sensor rate.
#include <cstdint>
#include <vector>

#include "core/trajectory.hpp"
#include "sim/world.hpp"

namespace revisit {

struct RouteConfig {
    double length = 3000.0;            ///< [m] route length: it ends at the first node beyond it, once all revisits are done
    int revisits = 6;                  ///< planned returns to streets driven earlier
    double opposite_fraction = 0.34;   ///< share of the planned revisits driven in the opposite direction
    int parallel_revisits = 1;         ///< extra returns along a new street parallel to one driven before (~1 block away)
    double min_revisit_gap = 300.0;    ///< [m] travelled before a street may be revisited on purpose
    double revisit_penalty = 4.0;      ///< exploration cost multiplier per earlier visit of a street
    double explore_radius = 350.0;     ///< [m] exploration targets lie at most this far (straight line)
    double corner_radius = 6.0;        ///< [m] corner rounding of the driven path (indoor: ~1 m)
    int start_node = -1;               ///< -1: the node nearest to the centre of the graph
};

/// Node sequence (consecutive nodes share an edge, no U-turns) with the requested revisits.
std::vector<int> PlanRoute(const StreetGraph& graph, const RouteConfig& config, std::uint64_t seed);

/// Centre-line polyline of a node sequence, moved `lane_offset` [m] to the right and resampled
/// every `spacing` [m], corners rounded over about `corner_radius` [m].
std::vector<Eigen::Vector2d> RoutePath(const StreetGraph& graph, const std::vector<int>& nodes, double lane_offset,
                                       double corner_radius = 6.0, double spacing = 1.0);

struct MotionConfig {
    double rate = 10.0;                ///< [Hz] poses per second (PlanSimulation uses the sensor's rate)
    double cruise_speed = 10.0;        ///< [m/s]
    double max_lateral_accel = 2.0;    ///< [m/s^2] sets the speed in turns
    double max_accel = 1.5;            ///< [m/s^2]
    double max_decel = 2.5;            ///< [m/s^2]
    double start_speed = 3.0;          ///< [m/s]
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
