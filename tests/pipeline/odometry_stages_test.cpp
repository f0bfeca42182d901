/// The odometry's stages (issue 19: the preparation of later scans runs ahead of the registration)
/// give the poses of registering the scans in a loop, on real scans, at any thread count.
#include <gtest/gtest.h>

#include <tbb/global_control.h>

#include "read_all.hpp"
#include "io/reader.hpp"
#include "odometry/lidar_odometry.hpp"
#include "pipeline/odometry_stages.hpp"
#include "support/test_data.hpp"

namespace revisit {
namespace {

Poses InStages(const PipelineConfig& config, std::vector<Scan> scans, std::size_t threads) {
    const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    OdometryStages stages(config);
    Poses poses;
    RunOdometryStages(stages, scans, [&](OdometryStages::Item& item, const Eigen::Isometry3d& T_world_sensor) {
        EXPECT_EQ(item.position, poses.size());
        poses.push_back(T_world_sensor);
    });
    return poses;
}

TEST(OdometryStages, GiveTheLoopsPosesOnKittiScansAtOneAndTwoThreads) {
    const auto dataset = test::SharedData("kitti00_first16");
    REVISIT_REQUIRE_DATA(dataset);
    const std::vector<Scan> scans = test::ReadAllScans(dataset);
    ASSERT_EQ(scans.size(), 16u);
    for (const bool deskew : {false, true}) {
        PipelineConfig config;
        config.odometry.deskew = deskew;
        config.input.follow_scene_scale = false;
        LidarOdometry loop(config.odometry);
        Poses expected;
        for (const auto& scan : scans) expected.push_back(loop.RegisterScan(scan));
        // The car drives ~1 m per scan: a real trajectory, not the identity.
        ASSERT_GT(expected.back().translation().norm(), 10.0);
        for (const std::size_t threads : {1, 2}) {
            const Poses staged = InStages(config, scans, threads);
            ASSERT_EQ(staged.size(), expected.size());
            for (std::size_t i = 0; i < staged.size(); ++i) {
                EXPECT_TRUE(staged[i].isApprox(expected[i], 0.0)) << "deskew " << deskew << ", " << threads << " threads, scan " << i;
            }
        }
    }
}

}  // namespace
}  // namespace revisit
