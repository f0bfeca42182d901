#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "core/se3.hpp"
#include "odometry/anderson.hpp"
#include "odometry/preprocess.hpp"
#include "odometry/registration.hpp"
#include "synthetic_world.hpp"

namespace revisit {
namespace {

constexpr double kDeg = M_PI / 180.0;

/// A sensor standing at `T` for the whole sweep (no motion distortion).
std::function<Eigen::Isometry3d(double)> Still(const Eigen::Isometry3d& T) {
    return [T](double) { return T; };
}

TEST(AndersonAccelerator, SolvesASlowLinearContractionInAFewSteps) {
    // G(y) = A y + b with A's spectral radius 0.95: plain iteration needs ~300 steps to reach 1e-6 of
    // the fixed point; a linear map of R^6 is extrapolated exactly once the history spans it.
    Eigen::Matrix<double, 6, 6> A = Eigen::Matrix<double, 6, 6>::Zero();
    for (int i = 0; i < 6; ++i) A(i, i) = 0.95 - 0.1 * i;
    A(0, 1) = 0.02;
    const AndersonAccelerator::Vector6 b = AndersonAccelerator::Vector6::Constant(0.01);
    const AndersonAccelerator::Vector6 fixed = (Eigen::Matrix<double, 6, 6>::Identity() - A).lu().solve(b);
    auto steps_to_converge = [&](int depth) {
        AndersonAccelerator anderson(depth);
        AndersonAccelerator::Vector6 y = AndersonAccelerator::Vector6::Zero();
        for (int step = 1; step <= 1000; ++step) {
            bool extrapolated = false;
            y = anderson.Next(y, A * y + b, extrapolated);
            if ((y - fixed).norm() < 1e-6 * fixed.norm()) return step;
        }
        return 1000;
    };
    EXPECT_GT(steps_to_converge(0), 250);
    EXPECT_LE(steps_to_converge(6), 10);
    EXPECT_LT(steps_to_converge(2), steps_to_converge(0) / 3);
}

TEST(AndersonAccelerator, IcpFromTurnedGuessesReachesThePlainIterationsPose) {
    // A car in a bend, registered from guesses turned 1-4 degrees off (the turn hypothesis' start):
    // plain point-to-point iterations crawl (18-58 here); the accelerated ones (fewer or more, case by
    // case) must end at the same fixed point: the same stopping test, only the path differs.
    const Poses route = test::DriveRoute(30, 2.0, 1.8, 2.0 * kDeg);
    const auto world = test::MakeCity(route, 6.0, 5);
    const auto pattern = test::SpinningPattern(32, 1000, -25.0, 3.0, 100.0);
    const int i = 25;
    VoxelHashMap map(1.0, 20);
    for (int k = i - 3; k < i; ++k) {
        const Scan still = test::CastScan(world, pattern, Still(route[k]), 0.01, k);
        auto points = VoxelDownsample(CropRange(still.points, 5.0, 100.0), 0.5);
        for (auto& p : points) p = route[k] * p;
        map.AddPoints(points);
    }
    const Scan scan = test::CastScan(world, pattern, Still(route[i]), 0.01, i);
    const auto source = VoxelDownsample(VoxelDownsample(CropRange(scan.points, 5.0, 100.0), 0.5), 1.5);
    for (const double offset_deg : {1.0, 2.0, 3.0, 4.0}) {
        Eigen::Isometry3d guess = route[i];
        guess.linear() = route[i].linear() * Eigen::AngleAxisd(offset_deg * kDeg, Eigen::Vector3d::UnitZ()).toRotationMatrix();
        IcpParams params;
        params.max_correspondence_distance = 1.5;
        params.kernel = 0.5 / 3.0;
        params.anderson_depth = 0;
        const IcpResult plain = RegisterPointsToMap(source, map, guess, params);
        params.anderson_depth = 2;
        const IcpResult accelerated = RegisterPointsToMap(source, map, guess, params);
        ASSERT_TRUE(plain.valid && plain.converged) << offset_deg << " deg";
        ASSERT_TRUE(accelerated.valid && accelerated.converged) << offset_deg << " deg";
        const Eigen::Isometry3d difference = plain.T_world_sensor.inverse() * accelerated.T_world_sensor;
        EXPECT_LT(difference.translation().norm(), 0.005) << offset_deg << " deg";
        EXPECT_LT(RotationAngle(difference) / kDeg, 0.01) << offset_deg << " deg";
        EXPECT_LT((plain.T_world_sensor.translation() - route[i].translation()).norm(), 0.05) << offset_deg << " deg";
    }
}

}  // namespace
}  // namespace revisit
