#include <gtest/gtest.h>

#include "optimization/smear_gate.hpp"

namespace revisit {
namespace {

RefinementResult Registered(double rms, int correspondences) {
    RefinementResult result;
    result.rms = rms;
    result.num_correspondences = correspondences;
    return result;
}

TEST(SmearGate, KeepsTheConfiguredGateUntilConsecutiveMapsShowMore) {
    SmearGate gate(1.5);
    EXPECT_DOUBLE_EQ(gate.MaxRms(0.25), 0.25);  // nothing measured yet
    // Good odometry: consecutive maps register well below the gate, which stays where it was.
    for (double rms : {0.10, 0.12, 0.11}) gate.Add(Registered(rms, 5000), 100);
    EXPECT_DOUBLE_EQ(gate.MedianRms(), 0.11);
    EXPECT_DOUBLE_EQ(gate.MaxRms(0.25), 0.25);
}

TEST(SmearGate, FollowsTheMedianOfSmearedMaps) {
    SmearGate gate(1.5);
    // A drifting odometry smears every map: consecutive (true) overlaps register at ~0.3 m.
    for (double rms : {0.29, 0.34, 0.30, 0.27, 0.31}) gate.Add(Registered(rms, 30000), 100);
    EXPECT_DOUBLE_EQ(gate.MedianRms(), 0.30);
    EXPECT_NEAR(gate.MaxRms(0.25), 0.45, 1e-12);
    // One outlier does not move the median (the lower one of an even count, Quantile's).
    gate.Add(Registered(3.0, 30000), 100);
    EXPECT_NEAR(gate.MaxRms(0.25), 0.45, 1e-12);
}

TEST(SmearGate, IgnoresPairsThatDidNotRegisterAndCanBeSwitchedOff) {
    SmearGate gate(1.5);
    gate.Add(Registered(0.9, 40), 100);  // too few correspondences: no overlap measured
    EXPECT_TRUE(gate.measured().empty());
    EXPECT_DOUBLE_EQ(gate.MaxRms(0.25), 0.25);
    SmearGate off(0.0);
    off.Add(Registered(0.4, 30000), 100);
    EXPECT_FALSE(off.active());
    EXPECT_DOUBLE_EQ(off.MaxRms(0.25), 0.25);
}

}  // namespace
}  // namespace revisit
