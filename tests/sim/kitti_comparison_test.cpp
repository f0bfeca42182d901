#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numeric>

#include "sim/presets.hpp"
#include "sim/scan_simulator.hpp"

namespace revisit {
namespace {

/// Statistics of a set of 64-beam scans that the comparison with real KITTI scans uses.
struct CloudStats {
    double points_per_scan = 0.0;
    std::array<double, 8> range_histogram{};  ///< fractions in [0,5,10,20,30,40,60,80,inf) m
    double elevation_p01 = 0.0;               ///< [deg] 1st percentile
    double elevation_p99 = 0.0;               ///< [deg] 99th percentile
    double lower_block_fraction = 0.0;        ///< points below -8.5 degrees (HDL-64E lower laser block)
    double median_range = 0.0;                ///< [m]
};

CloudStats Describe(const std::vector<std::vector<Eigen::Vector3f>>& scans) {
    static const double edges[9] = {0, 5, 10, 20, 30, 40, 60, 80, 1e9};
    CloudStats stats;
    std::vector<double> elevations, ranges;
    for (const auto& scan : scans)
        for (const auto& p : scan) {
            const double r = p.cast<double>().norm();
            ranges.push_back(r);
            elevations.push_back(std::atan2(p.z(), p.head<2>().norm()) * 180.0 / M_PI);
            for (int b = 0; b < 8; ++b)
                if (r >= edges[b] && r < edges[b + 1]) stats.range_histogram[b] += 1.0;
        }
    const double n = static_cast<double>(ranges.size());
    stats.points_per_scan = n / static_cast<double>(scans.size());
    for (auto& h : stats.range_histogram) h /= n;
    std::sort(elevations.begin(), elevations.end());
    std::sort(ranges.begin(), ranges.end());
    stats.elevation_p01 = elevations[elevations.size() / 100];
    stats.elevation_p99 = elevations[elevations.size() * 99 / 100];
    stats.lower_block_fraction =
        static_cast<double>(std::lower_bound(elevations.begin(), elevations.end(), -8.5) - elevations.begin()) / n;
    stats.median_range = ranges[ranges.size() / 2];
    return stats;
}

void Print(const char* name, const CloudStats& s) {
    std::printf("%-10s points/scan %7.0f  median range %5.1f m  elevation p1 %6.2f p99 %5.2f deg  lower block %.3f\n", name,
                s.points_per_scan, s.median_range, s.elevation_p01, s.elevation_p99, s.lower_block_fraction);
    std::printf("%-10s range histogram [0,5,10,20,30,40,60,80,inf) m:", name);
    for (double h : s.range_histogram) std::printf(" %.3f", h);
    std::printf("\n");
}

std::vector<Eigen::Vector3f> ReadKittiBin(const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    std::vector<float> values;
    float v[4];
    while (in.read(reinterpret_cast<char*>(v), sizeof(v))) values.insert(values.end(), v, v + 4);
    std::vector<Eigen::Vector3f> points;
    for (std::size_t i = 0; i + 3 < values.size(); i += 4) points.emplace_back(values[i], values[i + 1], values[i + 2]);
    return points;
}

TEST(KittiComparison, SimulatedCityScansLookLikeRealHdl64Scans) {
    const std::filesystem::path folder = std::filesystem::path(REVISIT_SHARED_DIR) / "data" / "kitti00_first16" / "velodyne";
    if (!std::filesystem::exists(folder)) GTEST_SKIP() << "real KITTI scans not available at " << folder;
    std::vector<std::vector<Eigen::Vector3f>> real;
    for (int i = 0; i < 16; ++i) {
        char name[16];
        std::snprintf(name, sizeof(name), "%06d.bin", i);
        real.push_back(ReadKittiBin(folder / name));
    }
    // Eight scans spread along the demo route.
    const SimConfig config = SimPreset("demo");
    const SimPlan plan = PlanSimulation(config);
    const RayCaster caster(plan.world);
    const auto rays = MakeRays(config.sensor, 0);
    std::vector<std::vector<Eigen::Vector3f>> simulated;
    for (int k = 0; k < 8; ++k) {
        const std::size_t index = (2 * k + 1) * plan.trajectory.size() / 16;
        SweepInput sweep;
        sweep.index = index;
        sweep.timestamp = plan.trajectory.timestamps[index];
        sweep.T_world_sensor = plan.trajectory.poses[index];
        sweep.T_world_sensor_start = sweep.T_world_sensor;
        simulated.push_back(SimulateScan(caster, config.sensor, rays, sweep, config.seed).points);
    }
    const CloudStats a = Describe(real), b = Describe(simulated);
    Print("KITTI 00", a);
    Print("simulated", b);
    EXPECT_NEAR(b.points_per_scan / a.points_per_scan, 1.0, 0.15);
    // Ring structure: the same vertical field of view and share of the lower laser block.
    EXPECT_NEAR(b.elevation_p01, a.elevation_p01, 1.5);
    EXPECT_NEAR(b.elevation_p99, a.elevation_p99, 1.5);
    EXPECT_NEAR(b.lower_block_fraction, a.lower_block_fraction, 0.1);
    // Range histograms overlap (histogram intersection) and the medians are of the same size.
    double overlap = 0.0;
    for (int i = 0; i < 8; ++i) overlap += std::min(a.range_histogram[i], b.range_histogram[i]);
    std::printf("range histogram intersection %.3f\n", overlap);
    EXPECT_GT(overlap, 0.8);
    EXPECT_NEAR(b.median_range / a.median_range, 1.0, 0.35);
}

}  // namespace
}  // namespace revisit
