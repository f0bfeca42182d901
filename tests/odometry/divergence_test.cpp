/// Issue 14: a stretch of empty or garbage scans in the middle of a drive is detected as divergence,
/// counted, and does not wreck the rest of the trajectory.
#include <gtest/gtest.h>

#include <random>

#include "odometry/lidar_odometry.hpp"
#include "synthetic_world.hpp"

namespace revisit {
namespace {

constexpr double kDeg = M_PI / 180.0;

TEST(OdometryDivergence, GarbageAndEmptyScansFallBackToThePredictionAndTheDriveRecovers) {
    const Poses route = test::DriveRoute(100, 1.2, 1.8, 1.0 * kDeg);
    const auto world = test::MakeCity(route, 6.0, 3);
    const auto pattern = test::SpinningPattern(32, 720, -24.8, 2.0, 100.0);
    LidarOdometry odometry;
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> coordinate(-40.f, 40.f);
    std::vector<std::size_t> fallbacks;
    for (std::size_t i = 0; i < route.size(); ++i) {
        Scan scan = test::CastScan(world, pattern, [&](double) { return route[i]; }, 0.01, static_cast<unsigned>(i));
        scan.index = i;
        if (i >= 40 && i < 44) {  // a sensor fault: returns scattered through free space
            for (auto& p : scan.points) p = {coordinate(rng), coordinate(rng), 0.25f * coordinate(rng)};
        } else if (i == 44 || i == 45) {  // then nothing at all
            scan.points.clear();
        }
        odometry.RegisterScan(scan);
        if (odometry.LastStats().degenerate) fallbacks.push_back(i);
    }
    // Every faulty scan kept the prediction; no good scan did.
    EXPECT_EQ(fallbacks, (std::vector<std::size_t>{40, 41, 42, 43, 44, 45}));
    EXPECT_EQ(odometry.NumDegenerateFrames(), 6u);
    // Constant velocity carried the drive over six frames: the end is still within 1% of the path.
    const Eigen::Isometry3d T_truth = route.front().inverse() * route.back();
    EXPECT_LT((odometry.poses().back().translation() - T_truth.translation()).norm(), 0.01 * PathLength(route));
}

}  // namespace
}  // namespace revisit
