#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>

#include "io/reader.hpp"
#include "sim/presets.hpp"

namespace revisit {
namespace {

std::filesystem::path TempPath(const std::string& name) {
    return std::filesystem::temp_directory_path() / ("revisit_sim_" + std::to_string(::getpid()) + "_" + name);
}

TEST(RoundTrip, KittiFolderReadsBackWithGroundTruth) {
    SimConfig config = SimPreset("tiny");
    config.max_scans = 5;
    const auto folder = TempPath("kitti");
    std::filesystem::remove_all(folder);
    const SimSummary summary = RunSimulation(config, folder, false);
    EXPECT_EQ(summary.scans, 5u);
    auto reader = OpenDataset(folder);
    std::size_t count = 0, points = 0;
    while (auto scan = reader->Next()) {
        ASSERT_TRUE(scan->T_world_sensor.has_value());
        points += scan->points.size();
        ++count;
    }
    EXPECT_EQ(count, 5u);
    EXPECT_EQ(points, summary.points);
    EXPECT_THROW(RunSimulation(config, folder, false), std::exception);  // refuses to overwrite without force
    std::filesystem::remove_all(folder);
}

TEST(RoundTrip, PlanarLaserRawlogReadsBackWithOdometry) {
    SimConfig config = SimPreset("indoor-2d-360");
    config.max_scans = 20;
    const auto file = TempPath("indoor.rawlog");
    const SimSummary summary = RunSimulation(config, file, true);
    EXPECT_EQ(summary.scans, 20u);
    EXPECT_TRUE(std::filesystem::exists(file.string() + ".sim.yaml"));
    auto reader = OpenDataset(file);
    std::size_t count = 0, points = 0;
    while (auto scan = reader->Next()) {
        EXPECT_TRUE(scan->T_world_sensor.has_value());
        EXPECT_TRUE(scan->T_odom_sensor.has_value());
        for (const auto& p : scan->points) ASSERT_NEAR(p.z(), 0.0f, 1e-4f);
        points += scan->points.size();
        ++count;
    }
    EXPECT_EQ(count, 20u);
    // Range scans store one range per beam: points within a few per cent (beams binned by angle).
    EXPECT_NEAR(static_cast<double>(points), static_cast<double>(summary.points), 0.05 * summary.points);
    std::filesystem::remove(file);
    std::filesystem::remove(file.string() + ".sim.yaml");
}

}  // namespace
}  // namespace revisit
