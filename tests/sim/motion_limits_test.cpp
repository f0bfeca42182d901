#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

#include "sim/presets.hpp"

namespace revisit {
namespace {

constexpr double kDegree = M_PI / 180.0;

/// Worst values over consecutive ground-truth poses (the sensor is mounted level on the car).
struct MotionStats {
    double max_yaw_rate = 0.0;         ///< [rad/s]
    double min_radius = 1e9;           ///< [m] distance / yaw change, while moving
    double max_yaw_accel = 0.0;        ///< [rad/s^2] change of the yaw rate per second
    double max_lateral_accel = 0.0;    ///< [m/s^2] speed * yaw rate
    std::size_t worst_radius_pose = 0;
};

MotionStats Measure(const Trajectory& trajectory) {
    MotionStats stats;
    double previous_rate = 0.0;
    for (std::size_t k = 1; k < trajectory.size(); ++k) {
        const Eigen::Matrix3d R0 = trajectory.poses[k - 1].linear(), R1 = trajectory.poses[k].linear();
        const double dyaw = std::remainder(std::atan2(R1(1, 0), R1(0, 0)) - std::atan2(R0(1, 0), R0(0, 0)), 2.0 * M_PI);
        const double dt = trajectory.timestamps[k] - trajectory.timestamps[k - 1];
        const double distance = (trajectory.poses[k].translation() - trajectory.poses[k - 1].translation()).head<2>().norm();
        const double rate = dyaw / dt;
        stats.max_yaw_rate = std::max(stats.max_yaw_rate, std::abs(rate));
        stats.max_lateral_accel = std::max(stats.max_lateral_accel, std::abs(rate) * distance / dt);
        if (distance > 0.05 && std::abs(dyaw) > 1e-9 && distance / std::abs(dyaw) < stats.min_radius)
            stats.min_radius = distance / std::abs(dyaw), stats.worst_radius_pose = k;
        if (k >= 2) stats.max_yaw_accel = std::max(stats.max_yaw_accel, std::abs(rate - previous_rate) / dt);
        previous_rate = rate;
    }
    return stats;
}

void ExpectCarLimits(const std::string& name, const Trajectory& trajectory) {
    ASSERT_GT(trajectory.size(), 100u) << name;
    const MotionStats stats = Measure(trajectory);
    std::cout << name << ": max yaw rate " << stats.max_yaw_rate / kDegree << " deg/s, min radius " << stats.min_radius
              << " m (pose " << stats.worst_radius_pose << "), max yaw-rate change " << stats.max_yaw_accel / kDegree
              << " deg/s^2, max lateral acceleration " << stats.max_lateral_accel << " m/s^2\n";
    EXPECT_LE(stats.max_yaw_rate, 35.0 * kDegree) << name;
    EXPECT_GE(stats.min_radius, 5.9) << name << " pose " << stats.worst_radius_pose;  // chords: a hair below 6 m
    EXPECT_LE(stats.max_yaw_accel, 20.0 * kDegree) << name;
    EXPECT_LE(stats.max_lateral_accel, 3.0) << name;
    // Corners are still driven: the limits do not come from never turning.
    EXPECT_GT(stats.max_yaw_rate, 15.0 * kDegree) << name;
}

TEST(MotionLimits, DemoDrivesCornersLikeACar) {
    const SimPlan plan = PlanSimulation(SimPreset("demo"));
    ExpectCarLimits("demo", plan.trajectory);
    // The rounded corners keep the route's revisits.
    int opposite = 0;
    for (const auto& r : plan.revisits) opposite += r.opposite ? 1 : 0;
    std::cout << "demo: " << plan.revisits.size() << " revisits, " << opposite << " opposite\n";
    EXPECT_GE(plan.revisits.size(), 5u);
    EXPECT_GE(opposite, 1);
}

TEST(MotionLimits, OtherDrivingPresetsToo) {
    for (const std::string name : {"tiny", "highway-64"}) {
        SimConfig config = SimPreset(name);
        config.route.length = std::min(config.route.length, 1500.0);
        ExpectCarLimits(name, PlanSimulation(config).trajectory);
    }
}

}  // namespace
}  // namespace revisit
