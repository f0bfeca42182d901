#include <gtest/gtest.h>

#include <random>

#include "pipeline/refinement_gate.hpp"

namespace revisit {
namespace {

/// A street 40 m long: the road and two facades 8 m high, 20 m apart, sampled every 0.25 m; each
/// surface as thick as `thickness` (the spread an odometry that drifts within a map leaves on it).
std::vector<Eigen::Vector3d> Street(double thickness, std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::normal_distribution<double> across(0.0, thickness);
    std::vector<Eigen::Vector3d> points;
    for (double x = -20.0; x <= 20.0; x += 0.25) {
        for (double y = -10.0; y <= 10.0; y += 0.25) points.emplace_back(x, y, across(rng));
        for (double z = 0.0; z <= 8.0; z += 0.25) {
            points.emplace_back(x, -10.0 + across(rng), z);
            points.emplace_back(x, 10.0 + across(rng), z);
        }
    }
    return points;
}

/// The next map starts 15 m further down the street: the same world seen from its own origin.
std::vector<Eigen::Vector3d> InNextMap(std::vector<Eigen::Vector3d> points) {
    for (auto& p : points) p.x() -= 15.0;
    return points;
}

Eigen::Isometry3d NextFromPrevious() {
    Eigen::Isometry3d T_query_ref = Eigen::Isometry3d::Identity();
    T_query_ref.translation().x() = -15.0;
    return T_query_ref;
}

TEST(RefinementGate, GoodOdometryKeepsTheConfiguredGate) {
    RefinementGate gate{PipelineConfig{}};
    ASSERT_TRUE(gate.active());
    for (std::uint32_t map = 1; map <= 3; ++map)
        gate.AddConsecutive(Street(0.02, 2 * map), InNextMap(Street(0.02, 2 * map + 1)), NextFromPrevious(), 100 * map);
    EXPECT_DOUBLE_EQ(gate.Refinement().max_rms, RefinementConfig{}.max_rms);
    EXPECT_FALSE(gate.Update().has_value());
}

TEST(RefinementGate, SmearedMapsRaiseTheGateAndSayWhereAndWhy) {
    RefinementGate gate{PipelineConfig{}};
    for (std::uint32_t map = 1; map <= 3; ++map)
        gate.AddConsecutive(Street(0.4, 2 * map), InNextMap(Street(0.4, 2 * map + 1)), NextFromPrevious(), 100 * map);
    const double raised = gate.Refinement().max_rms;
    EXPECT_GT(raised, RefinementConfig{}.max_rms);
    EXPECT_LT(raised, 1.0);  // a multiple of the surfaces' spread, not an open gate
    const auto update = gate.Update();
    ASSERT_TRUE(update.has_value());
    EXPECT_EQ(update->key, "refinement.max_rms");
    EXPECT_EQ(update->scan, 100u);  // the first map whose registration raised it
    EXPECT_DOUBLE_EQ(update->to, raised);
    EXPECT_NE(update->reason.find("smears"), std::string::npos);
}

TEST(RefinementGate, AGateChosenByTheUserOrForA2DLaserStaysFixed) {
    PipelineConfig explicit_gate;
    explicit_gate.refinement.max_rms = 0.3;
    PipelineConfig planar;
    planar.odometry.planar = true;
    for (const PipelineConfig& config : {explicit_gate, planar}) {
        RefinementGate gate{config};
        EXPECT_FALSE(gate.active());
        gate.AddConsecutive(Street(0.4, 1), InNextMap(Street(0.4, 2)), NextFromPrevious(), 100);
        EXPECT_DOUBLE_EQ(gate.Refinement().max_rms, config.refinement.max_rms);
        EXPECT_FALSE(gate.Update().has_value());
    }
}

}  // namespace
}  // namespace revisit
