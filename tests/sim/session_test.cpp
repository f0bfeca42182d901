// revisit simulate --session K: another route through the same world.
#include <gtest/gtest.h>

#include "sim/presets.hpp"
#include "sim/simulate.hpp"

namespace revisit {
namespace {

TEST(SimSession, AnotherSessionDrivesAnotherRouteThroughTheSameWorld) {
    SimConfig config = SimPreset("tiny");
    config.max_scans = 300;
    const SimPlan first = PlanSimulation(config);
    config.session = 1;
    const SimPlan second = PlanSimulation(config);
    EXPECT_EQ(SessionSeed(config), config.seed + 1000003u);
    // The same world: the same buildings, streets and cars.
    ASSERT_EQ(first.world.boxes.size(), second.world.boxes.size());
    for (std::size_t i = 0; i < first.world.boxes.size(); ++i)
        EXPECT_EQ(first.world.boxes[i].center, second.world.boxes[i].center) << "box " << i;
    EXPECT_EQ(first.world.streets.nodes.size(), second.world.streets.nodes.size());
    EXPECT_EQ(first.world.moving_cars.size(), second.world.moving_cars.size());
    // Another route: both start at the central street node, then part ways.
    ASSERT_EQ(first.trajectory.size(), 300u);
    ASSERT_EQ(second.trajectory.size(), 300u);
    EXPECT_LT((first.trajectory.poses.front().translation() - second.trajectory.poses.front().translation()).norm(), 10.0);
    EXPECT_GT((first.trajectory.poses.back().translation() - second.trajectory.poses.back().translation()).norm(), 20.0);
    // Session 0 is the preset's route, unchanged by the session mechanism.
    config.session = 0;
    EXPECT_EQ(SessionSeed(config), config.seed);
    EXPECT_TRUE(PlanSimulation(config).trajectory.poses.back().isApprox(first.trajectory.poses.back()));
}

}  // namespace
}  // namespace revisit
