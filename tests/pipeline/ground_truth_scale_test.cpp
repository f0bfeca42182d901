/// The ground-truth closures at the data's scale: on the shared 58 m Livox walk the paper's car
/// scale (pairs 200 m of travel apart) holds no pair, so precision, recall and F1 would count
/// nothing; the settings from the data give it pairs the detector is allowed to find.
#include <gtest/gtest.h>

#include <cstdio>

#include "config/config.hpp"
#include "evaluation/ground_truth_closures.hpp"
#include "io/trajectory_io.hpp"
#include "read_all.hpp"
#include "settings/auto_settings.hpp"
#include "test_data.hpp"

namespace revisit {
namespace {

GtClosures GroundTruth(const Poses& reference, const std::vector<Scan>& scans, const GtClosureConfig& config) {
    return ComputeGroundTruthClosures(
        reference,
        [&](std::size_t i) { return scans[i].points; },
        config);
}

TEST(GroundTruthScale, WalkGetsPairsTheDetectorMayFind) {
    const auto walk = test::SharedData("livox_handheld_walk");
    REVISIT_REQUIRE_DATA(walk);
    PipelineConfig config;
    ConfigureFromData(config, walk);
    // The detector's own skip of recent maps, within the odometry's range.
    EXPECT_GT(config.detector.skip_recent_travel, 0.0);
    EXPECT_EQ(config.ground_truth.min_travel, config.detector.skip_recent_travel);
    EXPECT_EQ(config.ground_truth.max_range, config.odometry.max_range);

    const Poses reference = ReadKittiPoses(walk / "poses.txt").poses;
    const std::vector<Scan> scans = test::ReadAllScans(walk);
    ASSERT_EQ(scans.size(), reference.size());
    const GtClosures at_data_scale = GroundTruth(reference, scans, config.ground_truth);
    const GtClosures at_car_scale = GroundTruth(reference, scans, GtClosureConfig{});
    EXPECT_EQ(at_car_scale.scan_pairs.size(), 0u);
    ASSERT_GT(at_data_scale.segment_pairs.size(), 0u);
    EXPECT_GT(at_data_scale.scan_pairs.size(), 1000u);
    // Every pair is a revisit: at least the skip apart along the path, and truly overlapping.
    for (const auto& pair : at_data_scale.segment_pairs) {
        const double travel = at_data_scale.segments[pair.later].start_travel - at_data_scale.segments[pair.earlier].start_travel;
        EXPECT_GE(travel, config.ground_truth.min_travel);
        EXPECT_GT(pair.overlap, config.ground_truth.min_overlap);
    }
    // The prediction's pair range from the same ground truth: a distance within the walk's range below
    // which the revisit pairs mostly close; the car scale has no candidates to measure it on.
    const double tau_d = OverlapDistance(at_data_scale);
    std::printf("tau_d from the walk's ground truth: %.1f m\n", tau_d);
    EXPECT_GT(tau_d, at_data_scale.distance_bin);
    EXPECT_LT(tau_d, config.ground_truth.max_range);
    EXPECT_EQ(OverlapDistance(at_car_scale), 0.0);
}

}  // namespace
}  // namespace revisit
