#pragma once
/// Test fixture: a 40 m square loop through a corridor (walls 4 m either side of the centre line),
/// driven 1 m per scan; scans are the wall points within range, in the sensor frame.
#include "core/se3.hpp"
#include "core/trajectory.hpp"

#include <Eigen/Core>
#include <cmath>
#include <vector>

namespace revisit::testing {

constexpr double kSquareSide = 40.0;  // [m]
constexpr double kLoopLength = 4.0 * kSquareSide;

/// Pose at arc length s along the square (counter-clockwise from the origin, heading along each side).
inline Eigen::Isometry3d SquareLoopPose(double s) {
    const double along = std::fmod(s, kLoopLength);
    const int side = static_cast<int>(along / kSquareSide);
    const double t = along - side * kSquareSide;
    const double corners[4][2] = {{0, 0}, {kSquareSide, 0}, {kSquareSide, kSquareSide}, {0, kSquareSide}};
    const double directions[4][2] = {{1, 0}, {0, 1}, {-1, 0}, {0, -1}};
    const double x = corners[side][0] + t * directions[side][0];
    const double y = corners[side][1] + t * directions[side][1];
    return PoseFromXYZRPY(x, y, 1.5, 0.0, 0.0, std::atan2(directions[side][1], directions[side][0]));
}

inline Poses SquareLoopRoute(std::size_t num_scans, double step = 1.0) {
    Poses poses;
    for (std::size_t i = 0; i < num_scans; ++i) poses.push_back(SquareLoopPose(step * static_cast<double>(i)));
    return poses;
}

/// Points on the inner and outer corridor walls, every 0.25 m, heights 0 .. 3 m.
inline std::vector<Eigen::Vector3d> CorridorWalls() {
    std::vector<Eigen::Vector3d> points;
    for (const double offset : {-4.0, 4.0}) {
        const double low = offset, high = kSquareSide - offset;  // the wall square's corners
        const double corners[5][2] = {{low, low}, {high, low}, {high, high}, {low, high}, {low, low}};
        for (int side = 0; side < 4; ++side) {
            const Eigen::Vector2d a(corners[side][0], corners[side][1]);
            const Eigen::Vector2d b(corners[side + 1][0], corners[side + 1][1]);
            const int steps = static_cast<int>(std::round((b - a).norm() / 0.25));
            for (int k = 0; k < steps; ++k) {
                const Eigen::Vector2d xy = a + (b - a) * (double(k) / steps);
                for (double z = 0.0; z <= 3.0; z += 0.5) points.emplace_back(xy.x(), xy.y(), z);
            }
        }
    }
    return points;
}

/// The wall points within `range` of the sensor, in the sensor frame.
inline std::vector<Eigen::Vector3f> VisiblePoints(const std::vector<Eigen::Vector3d>& world,
                                                  const Eigen::Isometry3d& T_world_sensor, double range) {
    std::vector<Eigen::Vector3f> points;
    const Eigen::Isometry3d T_sensor_world = T_world_sensor.inverse();
    for (const auto& p : world) {
        const Eigen::Vector3d local = T_sensor_world * p;
        if (local.norm() <= range) points.push_back(local.cast<float>());
    }
    return points;
}

}  // namespace revisit::testing
