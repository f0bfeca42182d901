#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "io/trajectory_io.hpp"
#include "sim/presets.hpp"

namespace revisit {
namespace {

TEST(AroundTrajectory, KittiRouteGetsStreetsThatNeverBlockIt) {
    const auto file = std::filesystem::path(REVISIT_SHARED_DIR) / "data" / "kitti_gt_poses" / "00.txt";
    if (!std::filesystem::exists(file)) GTEST_SKIP() << "KITTI ground-truth poses not available at " << file;
    SimConfig config = SimPreset("demo");
    config.world = WorldKind::kAroundTrajectory;
    config.trajectory_file = file;
    const SimPlan plan = PlanSimulation(config);
    const double given_length = PathLength(ReadPoses(file).poses);
    EXPECT_NEAR(PathLength(plan.trajectory.poses) / given_length, 1.0, 0.05);
    EXPECT_GT(plan.world.boxes.size(), 500u);
    EXPECT_GT(plan.world.cylinders.size(), 100u);
    // KITTI 00 returns to earlier streets several times.
    EXPECT_GE(plan.revisits.size(), 3u);
    // No object within the clearance of the driven path (box corners and edge midpoints checked).
    const double clearance = config.around.clearance - 0.5;  // resampling and corner rounding
    for (std::size_t k = 0; k < plan.trajectory.size(); k += 3) {
        const Eigen::Vector2d p = plan.trajectory.poses[k].translation().head<2>();
        for (const auto& box : plan.world.boxes) {
            const Eigen::Vector2d d = p - box.center;
            if (d.norm() > 60.0) continue;
            const double c = std::cos(box.yaw), s = std::sin(box.yaw);
            const Eigen::Vector2d local(c * d.x() + s * d.y(), -s * d.x() + c * d.y());
            const double outside = (local.cwiseAbs() - box.half_size).cwiseMax(0.0).norm();
            ASSERT_GT(outside, clearance - 2.5) << "pose " << k;  // corners are sampled, faces may come 2.5 m closer
        }
        for (const auto& pole : plan.world.cylinders) ASSERT_GT((pole.center - p).norm(), clearance) << "pose " << k;
    }
}

}  // namespace
}  // namespace revisit
