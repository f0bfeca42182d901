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
    // No building within the clearance of the driven path (box corners and edge midpoints checked), no
    // parked car, kerb or clutter within the near clearance: nothing blocks a 2 m wide vehicle.
    const double clearance = config.around.clearance - 0.5;  // resampling and corner rounding
    const double near_clearance = config.around.near_clearance - 0.5;
    for (std::size_t k = 0; k < plan.trajectory.size(); k += 3) {
        const Eigen::Vector2d p = plan.trajectory.poses[k].translation().head<2>();
        for (const auto& box : plan.world.boxes) {
            const Eigen::Vector2d d = p - box.center;
            if (d.norm() > 60.0) continue;
            const double c = std::cos(box.yaw), s = std::sin(box.yaw);
            const Eigen::Vector2d local(c * d.x() + s * d.y(), -s * d.x() + c * d.y());
            const double outside = (local.cwiseAbs() - box.half_size).cwiseMax(0.0).norm();
            const bool building = box.material == Material::kBuilding || box.material == Material::kGlass;
            // Corners are sampled, faces may come 3.5 m (buildings) or 1 m (cars, kerbs: shorter) closer.
            ASSERT_GT(outside, building ? clearance - 3.5 : near_clearance - 1.0) << "pose " << k;
        }
        for (const auto& pole : plan.world.cylinders) ASSERT_GT((pole.center - p).norm(), near_clearance) << "pose " << k;
    }
}

}  // namespace
}  // namespace revisit
