#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "core/error.hpp"
#include "core/se3.hpp"
#include "odometry/lidar_odometry.hpp"
#include "odometry/registration.hpp"
#include "synthetic_world.hpp"

namespace revisit {
namespace {

constexpr double kDeg = M_PI / 180.0;

/// A robot's planar drive through rooms: steps of 0.15 m with a slowly swinging yaw rate.
Poses IndoorRoute(int frames) {
    Poses route;
    double x = -12.0, y = -12.0, yaw = 0.6;
    for (int i = 0; i < frames; ++i) {
        route.push_back(PoseFromXYZRPY(x, y, 0.0, 0.0, 0.0, yaw));
        yaw += 3.0 * kDeg * std::sin(2.0 * M_PI * i / 80.0);
        x += 0.15 * std::cos(yaw);
        y += 0.15 * std::sin(yaw);
    }
    return route;
}

/// Wheel odometry with a 3% scale error and a yaw bias of 1 degree per metre.
Poses WheelOdometry(const Poses& route) {
    Poses odometry{route.front()};
    for (std::size_t i = 1; i < route.size(); ++i) {
        const Eigen::Isometry3d delta = route[i - 1].inverse() * route[i];
        const double step = delta.translation().norm();
        const Eigen::Isometry3d biased =
            PoseFromXYZRPY(1.03 * delta.translation().x(), 1.03 * delta.translation().y(), 0.0, 0.0, 0.0,
                           std::atan2(delta.linear()(1, 0), delta.linear()(0, 0)) + 1.0 * kDeg * step);
        odometry.push_back(odometry.back() * biased);
    }
    return odometry;
}

double MaxError(const Poses& estimated, const Poses& truth) {
    double worst = 0.0;
    for (std::size_t i = 0; i < estimated.size(); ++i) {
        const Eigen::Isometry3d T_truth = truth.front().inverse() * truth[i];
        worst = std::max(worst, (estimated[i].translation() - T_truth.translation()).norm());
    }
    return worst;
}

OdometryConfig PlanarConfig() {
    OdometryConfig config;
    config.planar = true;
    config.max_range = 30.0;
    config.min_range = 0.1;
    return config;
}

TEST(LidarOdometryPlanar, TwoDimensionalLaserBeatsDriftingWheelOdometry) {
    const Poses route = IndoorRoute(160);
    const auto world = test::MakeIndoor(route, 40.0, 0.8, 2);
    const auto pattern = test::PlanarPattern(360, 360.0, 30.0);
    const Poses wheel = WheelOdometry(route);
    for (const bool use_prior : {false, true}) {
        OdometryConfig config = PlanarConfig();
        config.use_prior = use_prior;
        LidarOdometry odometry(config);
        for (std::size_t i = 0; i < route.size(); ++i) {
            Scan scan = test::CastScan(world, pattern, [&](double) { return route[i]; }, 0.01, static_cast<unsigned>(i));
            scan.index = i;
            scan.T_odom_sensor = wheel[i];
            const Eigen::Isometry3d T = odometry.RegisterScan(scan);
            ASSERT_FALSE(odometry.LastStats().degenerate) << odometry.LastStats().warning;
            EXPECT_EQ(odometry.LastStats().prior_used, use_prior && i > 0);
            // Planar state space: z, roll and pitch stay exactly zero.
            EXPECT_EQ(T.translation().z(), 0.0);
            EXPECT_NEAR(T.linear()(2, 2), 1.0, 1e-12);
        }
        const double path = PathLength(route);
        const double wheel_error = MaxError(Poses(wheel.begin(), wheel.end()), route);
        const double laser_error = MaxError(odometry.poses(), route);
        EXPECT_LT(laser_error, 0.01 * path) << "prior " << use_prior;
        EXPECT_LT(laser_error, 0.25 * wheel_error) << "prior " << use_prior << ", wheel " << wheel_error << " m";
    }
}

/// The first `frames` sweeps of a straight synthetic drive.
void Drive(LidarOdometry& odometry, const test::World& world, const Poses& route, int frames) {
    const auto pattern = test::SpinningPattern(32, 720, -25.0, 3.0, 100.0);
    for (int i = 0; i < frames; ++i) {
        Scan scan = test::CastScan(world, pattern, [&](double) { return route[i]; }, 0.01, static_cast<unsigned>(i));
        scan.index = static_cast<std::size_t>(i);
        odometry.RegisterScan(scan);
        ASSERT_FALSE(odometry.LastStats().degenerate) << odometry.LastStats().warning;
    }
}

void ExpectConstantVelocityWithWarning(const LidarOdometry& odometry, const std::string& warning_part) {
    const Poses& poses = odometry.poses();
    const std::size_t n = poses.size();
    ASSERT_GE(n, 3u);
    const Eigen::Isometry3d expected = poses[n - 2] * (poses[n - 3].inverse() * poses[n - 2]);
    EXPECT_TRUE(poses.back().matrix().allFinite());
    // Equal up to the re-orthonormalization of the rotation.
    EXPECT_LT((poses.back().translation() - expected.translation()).norm(), 1e-6);
    EXPECT_LT(RotationAngle(poses.back().inverse() * expected), 1e-6);
    EXPECT_TRUE(odometry.LastStats().degenerate);
    EXPECT_NE(odometry.LastStats().warning.find(warning_part), std::string::npos) << odometry.LastStats().warning;
}

TEST(LidarOdometryDegenerate, EmptyOutOfRangeAndPlanarScansGetTheConstantVelocityGuess) {
    const Poses street = test::DriveRoute(14, 1.0, 1.8, 0.0);
    const auto world = test::MakeCity(street, 5.0, 9);
    LidarOdometry odometry;
    Drive(odometry, world, street, 10);
    ASSERT_FALSE(HasFatalFailure());

    odometry.RegisterScan(Scan{});
    ExpectConstantVelocityWithWarning(odometry, "points left");

    Scan far_away;
    for (int k = 0; k < 1000; ++k) far_away.points.emplace_back(150.0f + k * 0.01f, 3.0f, 1.0f);
    odometry.RegisterScan(far_away);
    ExpectConstantVelocityWithWarning(odometry, "points left");

    test::World flat;  // the ground plane alone: translation along it is unobservable
    const auto pattern = test::SpinningPattern(32, 720, -25.0, -2.0, 100.0);
    odometry.RegisterScan(test::CastScan(flat, pattern, [](double) { return PoseFromXYZRPY(0, 0, 1.8, 0, 0, 0); }, 0.0, 1));
    ExpectConstantVelocityWithWarning(odometry, "single plane");
    EXPECT_EQ(odometry.NumDegenerateFrames(), 3u);

    // Back to real structure: tracking resumes from the predicted poses.
    const Eigen::Isometry3d T_next = street[13];
    Scan scan = test::CastScan(world, test::SpinningPattern(32, 720, -25.0, 3.0, 100.0), [&](double) { return T_next; }, 0.01, 99);
    const Eigen::Isometry3d T = odometry.RegisterScan(scan);
    EXPECT_FALSE(odometry.LastStats().degenerate) << odometry.LastStats().warning;
    EXPECT_LT((T.translation() - (street.front().inverse() * T_next).translation()).norm(), 0.1);
    EXPECT_LT(RotationAngle(T.inverse() * street.front().inverse() * T_next), 1.0 * kDeg);
}

TEST(LidarOdometryDegenerate, ImpossibleConfigurationIsRejected) {
    OdometryConfig config;
    config.min_range = 200.0;
    EXPECT_THROW(LidarOdometry{config}, ConfigError);
    config = OdometryConfig{};
    config.max_points_per_voxel = 0;
    EXPECT_THROW(LidarOdometry{config}, ConfigError);
}

}  // namespace
}  // namespace revisit
