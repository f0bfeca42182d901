#include <gtest/gtest.h>

#include "core/se3.hpp"
#include "sim/odometry_noise.hpp"

namespace revisit {
namespace {

Trajectory Straight(std::size_t n, double step) {
    Trajectory t;
    for (std::size_t k = 0; k < n; ++k) {
        t.timestamps.push_back(0.1 * k);
        t.poses.push_back(PoseFromXYZRPY(step * k, 0, 1.7, 0, 0, 0));
    }
    return t;
}

TEST(SimulateOdometry, DriftsWithScaleAndYawBias) {
    const Trajectory truth = Straight(1000, 1.0);  // 1 km at 10 m/s
    OdometryNoiseConfig config;
    config.translation_noise = 0.0;
    config.rotation_noise = 0.0;
    config.yaw_bias_random_walk = 0.0;
    const Poses odometry = SimulateOdometry(truth, config, 1);
    ASSERT_EQ(odometry.size(), truth.size());
    EXPECT_TRUE(odometry.front().isApprox(truth.poses.front()));
    // 1% scale: 999 m driven are measured as 1008.99 m of path; the yaw bias bends it.
    EXPECT_NEAR(PathLength(odometry), 999.0 * 1.01, 1e-6);
    const double heading = RotationAngle(truth.poses.back().inverse() * odometry.back());
    EXPECT_NEAR(heading, config.yaw_rate_bias * 99.9, 1e-3);
    EXPECT_GT((odometry.back().translation() - truth.poses.back().translation()).norm(), 20.0);
}

TEST(SimulateOdometry, IsDeterministicPerSeedAndGrowsWithDistance) {
    const Trajectory truth = Straight(600, 1.0);
    const Poses a = SimulateOdometry(truth, {}, 5), b = SimulateOdometry(truth, {}, 5), c = SimulateOdometry(truth, {}, 6);
    EXPECT_TRUE(a.back().isApprox(b.back(), 0.0));
    EXPECT_FALSE(a.back().isApprox(c.back(), 1e-9));
    const double early = (a[100].translation() - truth.poses[100].translation()).norm();
    const double late = (a[599].translation() - truth.poses[599].translation()).norm();
    EXPECT_GT(late, early);
}

}  // namespace
}  // namespace revisit
