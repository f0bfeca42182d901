#include <gtest/gtest.h>

#include <tbb/global_control.h>

#include "core/se3.hpp"
#include "kitti_scans.hpp"
#include "odometry/lidar_odometry.hpp"
#include "odometry/preprocess.hpp"
#include "odometry/registration.hpp"

namespace revisit {
namespace {

#define REQUIRE_KITTI() \
    if (!test::HaveKitti()) GTEST_SKIP() << "no KITTI scans at " << test::KittiDir()

Scan Transformed(const Scan& scan, const Eigen::Isometry3d& T_new_old) {
    Scan moved = scan;
    for (auto& p : moved.points) p = (T_new_old * p.cast<double>()).cast<float>();
    return moved;
}

TEST(LidarOdometryKitti, RecoversKnownMotionOfARealScan) {
    REQUIRE_KITTI();
    const Scan scan = test::LoadKittiScan(0);
    // The sensor moves by T_true: the same world seen from there is T_true^-1 * points.
    const Eigen::Isometry3d T_true = PoseFromXYZRPY(0.9, -0.35, 0.05, 0.01, -0.008, 3.0 * M_PI / 180.0);
    LidarOdometry odometry;
    odometry.RegisterScan(scan);
    Scan moved = Transformed(scan, T_true.inverse());
    moved.index = 1;
    const Eigen::Isometry3d T_estimated = odometry.RegisterScan(moved);
    EXPECT_FALSE(odometry.LastStats().degenerate) << odometry.LastStats().warning;
    EXPECT_LT((T_estimated.translation() - T_true.translation()).norm(), 0.02);
    EXPECT_LT(RotationAngle(T_estimated.inverse() * T_true) * 180.0 / M_PI, 0.1);
}

TEST(LidarOdometryKitti, SixteenFramesEndAtTheIcpConsensusNotTheGroundTruth) {
    REQUIRE_KITTI();
    std::vector<Scan> scans;
    for (int i = 0; i < 16; ++i) scans.push_back(test::LoadKittiScan(i));
    for (const IcpKernel kernel : {IcpKernel::kPaper, IcpKernel::kLater}) {
        OdometryConfig config;
        config.kernel = kernel;
        LidarOdometry odometry(config);
        std::vector<double> steps;
        for (const Scan& scan : scans) {
            odometry.RegisterScan(scan);
            EXPECT_FALSE(odometry.LastStats().degenerate) << odometry.LastStats().warning;
            const auto& poses = odometry.poses();
            ASSERT_TRUE(poses.back().matrix().allFinite());
            if (poses.size() > 1) steps.push_back((poses.back().translation() - poses[poses.size() - 2].translation()).norm());
        }
        const Eigen::Vector3d end = odometry.poses().back().translation();
        // DATA.md: two independent ICPs put frame 15 at ~11.76 m forward (ground truth says 12.87 m).
        // Measured: 11.71 m (paper kernel), 11.72 m (later kernel).
        EXPECT_NEAR(end.x(), 11.76, 0.15);
        EXPECT_GT(end.y(), 0.2);  // drifting left like the ground truth (0.70 m) does
        EXPECT_LT(end.y(), 0.7);
        // Steps grow from ~0.70 m to ~0.89 m.
        EXPECT_NEAR(steps.front(), 0.70, 0.06);
        EXPECT_NEAR(steps.back(), 0.89, 0.06);
        EXPECT_LT(steps.front(), steps.back());
    }
}

TEST(LidarOdometryKitti, PosesAreIdenticalWithOneAndTwoThreads) {
    REQUIRE_KITTI();
    auto run = [](int threads) {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
        LidarOdometry odometry;
        for (int i = 0; i < 6; ++i) odometry.RegisterScan(test::LoadKittiScan(i));
        return odometry.poses();
    };
    const Poses one = run(1);
    const Poses two = run(2);
    ASSERT_EQ(one.size(), two.size());
    // Deterministic reduction: bit-identical, not merely close.
    for (std::size_t i = 0; i < one.size(); ++i) EXPECT_EQ(one[i].matrix(), two[i].matrix()) << "frame " << i;
}

}  // namespace
}  // namespace revisit

