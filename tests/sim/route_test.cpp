#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "core/error.hpp"
#include "sim/presets.hpp"

namespace revisit {
namespace {

/// The demo's planned route, checked only from its ground truth.
class DemoRoute : public ::testing::Test {
  protected:
    static void SetUpTestSuite() { plan_ = new SimPlan(PlanSimulation(SimPreset("demo"))); }
    static void TearDownTestSuite() { delete plan_; }
    static SimPlan* plan_;
};
SimPlan* DemoRoute::plan_ = nullptr;

TEST_F(DemoRoute, HasTheRequestedRevisitsIncludingAnOppositeOne) {
    const auto& revisits = plan_->revisits;
    EXPECT_GE(revisits.size(), 5u);
    int opposite = 0, same = 0;
    for (const auto& r : revisits) {
        EXPECT_LT(r.min_distance, RevisitConfig{}.radius);
        // The earlier pose really is far back along the route.
        const auto travelled = CumulativeDistance(plan_->trajectory.poses);
        EXPECT_GT(travelled[r.last] - travelled[r.reference], RevisitConfig{}.min_gap);
        if (r.heading_difference > 150.0 * M_PI / 180.0) ++opposite;
        if (r.heading_difference < 30.0 * M_PI / 180.0) ++same;
    }
    EXPECT_GE(opposite, 1);
    EXPECT_GE(same, 3);
}

TEST_F(DemoRoute, IsAFewKilometresAtTenHertzWithRealisticSpeed) {
    const auto& trajectory = plan_->trajectory;
    const double length = PathLength(trajectory.poses);
    EXPECT_GT(length, 2000.0);
    EXPECT_LT(length, 5000.0);
    ASSERT_TRUE(trajectory.has_timestamps());
    double max_speed = 0.0, max_accel = 0.0, previous_speed = 0.0;
    for (std::size_t k = 1; k < trajectory.size(); ++k) {
        const double dt = trajectory.timestamps[k] - trajectory.timestamps[k - 1];
        ASSERT_NEAR(dt, 0.1, 1e-9);
        const double speed = (trajectory.poses[k].translation() - trajectory.poses[k - 1].translation()).norm() / dt;
        max_speed = std::max(max_speed, speed);
        if (k > 1) max_accel = std::max(max_accel, std::abs(speed - previous_speed) / dt);
        previous_speed = speed;
    }
    EXPECT_LT(max_speed, SimPreset("demo").motion.cruise_speed * 1.05);
    EXPECT_LT(max_accel, 5.0);  // no jumps: smooth corners, bounded acceleration (1.5-2.5 m/s^2 planned)
    // The sensor stays at its mounting height above the ground and level within the ground's slope.
    for (std::size_t k = 0; k < trajectory.size(); k += 50) {
        const Eigen::Vector3d p = trajectory.poses[k].translation();
        EXPECT_NEAR(p.z() - plan_->world.ground.Height(p.x(), p.y()), 1.73, 0.05);
        EXPECT_GT(trajectory.poses[k].linear()(2, 2), std::cos(0.1));
    }
}

TEST_F(DemoRoute, NeverDrivesThroughAnObject) {
    // Every static object is at least half a metre away from every sensor position.
    const auto& world = plan_->world;
    for (std::size_t k = 0; k < plan_->trajectory.size(); k += 5) {
        const Eigen::Vector3d p = plan_->trajectory.poses[k].translation();
        for (const auto& box : world.boxes) {
            if (box.z_min > p.z() + 0.3) continue;  // overhead (lamp arms)
            const Eigen::Vector2d d = p.head<2>() - box.center;
            const double c = std::cos(box.yaw), s = std::sin(box.yaw);
            const Eigen::Vector2d local(c * d.x() + s * d.y(), -s * d.x() + c * d.y());
            const Eigen::Vector2d outside = (local.cwiseAbs() - box.half_size).cwiseMax(0.0);
            ASSERT_GT(outside.norm(), 0.5) << "pose " << k << " inside a box";
        }
        for (const auto& pole : world.cylinders)  // poles, trunks, roundabout islands
            ASSERT_GT((pole.center - p.head<2>()).norm(), pole.radius + 0.5) << "pose " << k << " in a pole";
    }
}

TEST_F(DemoRoute, ParkedCarsDifferBetweenVisitsAndTrafficMoves) {
    const auto& world = plan_->world;
    const auto& trajectory = plan_->trajectory;
    auto visible_cars = [&](std::size_t pose, double time) {
        std::vector<std::size_t> cars;
        const Eigen::Vector2d p = trajectory.poses[pose].translation().head<2>();
        for (std::size_t i = 0; i < world.boxes.size(); ++i) {
            const auto& box = world.boxes[i];
            if (box.material != Material::kCar || (box.center - p).norm() > 50.0) continue;
            if (time >= box.visible_from && time <= box.visible_until) cars.push_back(i);
        }
        return cars;
    };
    int changed = 0;
    for (const auto& r : plan_->revisits) {
        const std::size_t now = (r.first + r.last) / 2;
        const auto before = visible_cars(r.reference, trajectory.timestamps[r.reference]);
        const auto after = visible_cars(r.reference, trajectory.timestamps[now]);  // same place, later
        EXPECT_FALSE(before.empty() && after.empty());
        changed += before != after;
    }
    EXPECT_GE(changed, 2);
    ASSERT_FALSE(world.moving_cars.empty());
    const OrientedBox a = world.moving_cars.front().BoxAt(0.0, world.ground), b = world.moving_cars.front().BoxAt(1.0, world.ground);
    EXPECT_NEAR((a.center - b.center).norm(), world.moving_cars.front().speed, 0.05 * world.moving_cars.front().speed);
}

TEST(PlanRoute, OppositeRevisitsAppearWhenAsked) {
    CityConfig city;
    city.blocks_x = 4;
    city.blocks_y = 4;
    const World world = GenerateCity(city, 11);
    auto count_opposite = [&](double fraction) {
        RouteConfig route;
        route.length = 2500.0;
        route.revisits = 4;
        route.opposite_fraction = fraction;
        const auto nodes = PlanRoute(world.streets, route, 11);
        for (std::size_t i = 2; i < nodes.size(); ++i) EXPECT_NE(nodes[i], nodes[i - 2]) << "U-turn at " << i;
        const auto path = RoutePath(world.streets, nodes, world.lane_offset);
        const Trajectory trajectory = DrivePath(path, world.ground, MotionConfig{}, 11);
        int opposite = 0;
        for (const auto& r : FindRevisits(trajectory.poses)) opposite += r.heading_difference > 150.0 * M_PI / 180.0;
        return opposite;
    };
    const int asked = count_opposite(1.0), not_asked = count_opposite(0.0);
    EXPECT_GE(asked, 2);
    EXPECT_GT(asked, not_asked);
}

TEST(SimPreset, EveryNameBuildsAPlanWithScans) {
    for (const auto& name : SimPresetNames()) {
        SimConfig config = SimPreset(name);
        config.route.length = std::min(config.route.length, 400.0);
        config.route.revisits = 1;
        const SimPlan plan = PlanSimulation(config);
        EXPECT_GT(plan.trajectory.size(), 20u) << name;
        EXPECT_GT(plan.world.NumPrimitives(), 50u) << name;
        EXPECT_EQ(plan.odometry.size(), plan.trajectory.size()) << name;
        // The sensor never starts or passes inside an object (roundabout islands, poles, boxes).
        for (std::size_t k = 0; k < plan.trajectory.size(); k += 10) {
            const Eigen::Vector2d p = plan.trajectory.poses[k].translation().head<2>();
            for (const auto& pole : plan.world.cylinders)
                ASSERT_GT((pole.center - p).norm(), pole.radius + 0.3) << name << " pose " << k;
            for (const auto& box : plan.world.boxes) {
                if (box.z_min > plan.trajectory.poses[k].translation().z() + 0.3) continue;  // overhead
                const Eigen::Vector2d d = p - box.center;
                const double c = std::cos(box.yaw), s = std::sin(box.yaw);
                const Eigen::Vector2d local(c * d.x() + s * d.y(), -s * d.x() + c * d.y());
                ASSERT_GT((local.cwiseAbs() - box.half_size).cwiseMax(0.0).norm(), 0.3) << name << " pose " << k;
            }
        }
    }
    EXPECT_THROW(SimPreset("no-such-preset"), ConfigError);
}

TEST(SimPreset, LongDrivesExploreAndComeBackAfterLongStretches) {
    // The paper's highway scale: 25 km. The route is planned only (no rays), so this is cheap.
    const SimPlan plan = PlanSimulation(WithRouteLength(SimPreset("highway-64"), 25000.0));
    const double length = PathLength(plan.trajectory.poses);
    EXPECT_GT(length, 25000.0);
    EXPECT_LT(length, 30000.0);
    EXPECT_GT(plan.trajectory.size(), 9000u);  // 25 m/s at 10 Hz
    const auto travelled = CumulativeDistance(plan.trajectory.poses);
    int opposite = 0, after_long_stretch = 0;
    for (const auto& r : plan.revisits) {
        opposite += r.opposite ? 1 : 0;
        after_long_stretch += travelled[r.first] - travelled[r.reference] > 2000.0 ? 1 : 0;
    }
    EXPECT_GE(opposite, 1);
    EXPECT_GE(after_long_stretch, 3);
    // Most of the drive is new ground: the world grew with the route.
    std::size_t far_from_earlier = 0;
    for (std::size_t k = 0; k < plan.trajectory.size(); k += 50) {
        double nearest = std::numeric_limits<double>::infinity();
        for (std::size_t j = 0; j + 300 < k; j += 5)
            nearest = std::min(nearest, (plan.trajectory.poses[k].translation() - plan.trajectory.poses[j].translation()).norm());
        far_from_earlier += nearest > 30.0 ? 1 : 0;
    }
    EXPECT_GT(far_from_earlier, plan.trajectory.size() / 50 / 3);
    // A city stretches the same way; indoor floors and lengths out of range are refused.
    const SimConfig city = WithRouteLength(SimPreset("city-16"), 10000.0);
    EXPECT_GT(city.city.blocks_x, SimPreset("city-16").city.blocks_x);
    EXPECT_THROW(WithRouteLength(SimPreset("indoor-2d-180"), 1000.0), ConfigError);
    EXPECT_THROW(WithRouteLength(SimPreset("demo"), 10.0), ConfigError);
}

}  // namespace
}  // namespace revisit
