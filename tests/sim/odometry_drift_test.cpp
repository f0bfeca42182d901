// The project's odometry with its default settings on simulated worlds must behave as on real
// data (issue 15): travel within 2% of the truth, no lock at zero motion, KITTI-style drift.
// Shortened routes so the test takes seconds; the full figures are in src/sim/README.md.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <vector>

#include "core/trajectory.hpp"
#include "evaluation/trajectory_metrics.hpp"
#include "odometry/lidar_odometry.hpp"
#include "sim/presets.hpp"
#include "sim/scan_simulator.hpp"

namespace revisit {
namespace {

namespace fs = std::filesystem;

struct DriftResult {
    double true_travel = 0.0;       ///< [m]
    double estimated_travel = 0.0;  ///< [m]
    std::size_t longest_lock = 0;   ///< scans in a row with < 5% of the true step while moving
    double segment_percent = 0.0;   ///< KITTI segment error over 100 m segments [%]
};

/// Simulates the first `scans` scans of `config` and runs the odometry (by default with the defaults of
/// configs/default.yaml) on them.
DriftResult Drive(SimConfig config, std::size_t scans, const OdometryConfig& odometry_config = {}) {
    config.max_scans = scans;
    const SimPlan plan = PlanSimulation(config);
    const RayCaster caster(plan.world);
    LidarOdometry odometry(odometry_config);
    for (std::size_t k = 0; k < plan.trajectory.size(); ++k) {
        SweepInput sweep;
        sweep.index = k;
        sweep.timestamp = plan.trajectory.timestamps[k];
        sweep.T_world_sensor = plan.trajectory.poses[k];
        sweep.T_world_sensor_start = plan.trajectory.poses[k > 0 ? k - 1 : 0];
        for (const auto& car : plan.world.moving_cars) sweep.dynamic_boxes.push_back(car.BoxAt(sweep.timestamp, plan.world.ground));
        Scan scan = SimulateScan(caster, config.sensor, MakeRays(config.sensor, k), sweep, config.seed);
        odometry.RegisterScan(scan);
    }
    const Poses& estimate = odometry.poses();
    const Poses& truth = plan.trajectory.poses;
    DriftResult result;
    result.true_travel = PathLength(truth);
    result.estimated_travel = PathLength(estimate);
    std::size_t run = 0;
    for (std::size_t k = 1; k < truth.size(); ++k) {
        const double step = (truth[k].translation() - truth[k - 1].translation()).norm();
        const double estimated = (estimate[k].translation() - estimate[k - 1].translation()).norm();
        run = step > 0.2 && estimated < 0.05 * step ? run + 1 : 0;
        result.longest_lock = std::max(result.longest_lock, run);
    }
    KittiSegmentConfig segments;
    segments.lengths = {100.0};
    result.segment_percent = ComputeKittiErrors(estimate, truth, segments).translation_percent;
    std::printf("%s: %zu scans, travel %.1f m estimated / %.1f m true, longest lock %zu scans, 100 m segment error %.2f%%\n",
                config.name.c_str(), truth.size(), result.estimated_travel, result.true_travel, result.longest_lock,
                result.segment_percent);
    return result;
}

void ExpectRealistic(const DriftResult& r) {
    EXPECT_NEAR(r.estimated_travel / r.true_travel, 1.0, 0.02);
    EXPECT_LE(r.longest_lock, 2u) << "the odometry stalled at zero motion";
    EXPECT_LT(r.segment_percent, 2.0);
}

TEST(OdometryDrift, DefaultOdometryFollowsTheDemoCity) {
    // From rest: the start is where a degenerate world locked the odometry (99 scans on the old demo city).
    ExpectRealistic(Drive(SimPreset("demo"), 150));
}

TEST(OdometryDrift, DefaultOdometryFollowsAWorldAlongKitti00) {
    const fs::path route = fs::path(REVISIT_SHARED_DIR) / "data" / "kitti_gt_poses" / "00.txt";
    if (!fs::exists(route)) GTEST_SKIP() << "KITTI 00 ground truth not available at " << route;
    SimConfig config = SimPreset("city-64");
    config.name = "along KITTI 00";
    config.world = WorldKind::kAroundTrajectory;
    config.trajectory_file = route;
    config.around.city = config.city;
    ExpectRealistic(Drive(config, 150));
}

TEST(OdometryDrift, SixteenBeamCityRegistersWithPointToPlane) {
    // city-16's rings are 2 deg apart: with KISS-ICP's point-to-point residual the upward rings' sparse
    // lines on walls pull the estimate nose-up (these 300 scans: 4.28% on 100 m segments; 600 scans with
    // the settings from the data: 6.11%, src/sim/README.md). The settings from the data choose
    // point-to-plane for rings >= 1 deg apart, as here. A world change that made a sparse sensor's
    // ground and streets unregistrable would fail this too.
    OdometryConfig odometry;
    odometry.residual = IcpResidual::kPointToPlane;
    ExpectRealistic(Drive(SimPreset("city-16"), 300, odometry));
}

TEST(OdometryDrift, DefaultOdometryFollowsTheHighwayAtSpeed) {
    // Accelerating to 20 m/s (2 m per scan). Before the verge was modelled (banks, tree belts, bridges) the
    // odometry held 0.5 m per scan from scan 50 on (-40% travel over 600 scans; these 120 scans: 58.5 m
    // estimated for 141.9 m, segment error 61%): a bare verge repeats along the road.
    ExpectRealistic(Drive(SimPreset("highway-64"), 120));
}

}  // namespace
}  // namespace revisit
