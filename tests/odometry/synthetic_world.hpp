#pragma once
/// Test helper: analytic ray casting in worlds of boxes and a ground plane, so the odometry
/// tests have exact ground truth without depending on the simulator module.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <functional>
#include <vector>

#include "core/scan.hpp"
#include "core/trajectory.hpp"

namespace revisit::test {

struct Box {
    Eigen::Vector3d lo, hi;  ///< [m] corners before the rotation
    double yaw = 0.0;        ///< [rad] rotation about the vertical axis through the box's centre

    /// A world point in the box's unrotated frame (where the box is [lo, hi]).
    Eigen::Vector3d Unrotate(const Eigen::Vector3d& p) const;
    /// The footprint's four corners in the world.
    std::vector<Eigen::Vector2d> Corners() const;
};

struct World {
    std::vector<Box> boxes;
    bool has_ground = true;  ///< the plane z = 0
};

/// A sensor's rays in its own frame, each with the normalized sweep time s in [0, 1] at which it fires.
struct RayPattern {
    std::vector<Eigen::Vector3d> directions;  ///< unit vectors
    std::vector<double> sweep_times;
    double max_range = 100.0;  ///< [m] no return beyond
};

/// Spinning LiDAR: `beams` elevations in [min_deg, max_deg], `columns` azimuths, sweeping
/// clockwise (s = 0.5 (1 - azimuth / pi)), like KITTI's HDL-64E.
RayPattern SpinningPattern(int beams, int columns, double min_elevation_deg, double max_elevation_deg, double max_range);
/// Livox-like non-repetitive rosette inside a cone of `fov_deg`, looking along +x.
RayPattern RosettePattern(int rays, double fov_deg, double max_range);
/// Planar 2D laser: `beams` over `fov_deg` in the sensor's x-y plane.
RayPattern PlanarPattern(int beams, double fov_deg, double max_range);

/// Boxes ("buildings" and poles) scattered around `route` but at least `clearance` [m] from it.
World MakeCity(const Poses& route, double clearance, unsigned seed);
/// Rooms and corridors for a 2D laser: walls of a `size` [m] square floor plan with inner walls
/// and furniture, none within `clearance` of `route`.
World MakeIndoor(const Poses& route, double size, double clearance, unsigned seed);

/// The scan seen from a sensor whose pose at sweep time s is `T_world_sensor_at(s)`; each point
/// is in the sensor frame at its own firing time (motion distortion when the pose changes with s).
/// Gaussian range noise of `range_noise` [m].
Scan CastScan(const World& world, const RayPattern& pattern,
              const std::function<Eigen::Isometry3d(double)>& T_world_sensor_at, double range_noise, unsigned seed);

/// Poses along a smooth S-shaped drive of `frames` steps of up to `step` [m] (starting from rest
/// at 3 m/s^2 for 10 Hz sweeps), at `height` [m] above ground, with suspension bounce, roll, pitch.
Poses DriveRoute(int frames, double step, double height, double yaw_rate_per_step);

}  // namespace revisit::test
