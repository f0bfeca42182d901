// `sim:PRESET` datasets: the scans the simulator writes, read without writing them.
#include <gtest/gtest.h>

#include "core/error.hpp"
#include "io/reader.hpp"
#include "sim/presets.hpp"
#include "sim/sim_reader.hpp"
#include "test_data.hpp"

namespace revisit {
namespace {

TEST(SimReader, ReadsTheScansTheKittiFolderOfTheSameConfigurationHolds) {
    SimConfig config = SimPreset("tiny");
    config.max_scans = 5;
    test::TempDir dir;
    RunSimulation(config, dir / "tiny", true);
    auto folder = OpenDataset(dir / "tiny");
    auto simulated = OpenSimulation(config, "sim:tiny");
    ASSERT_EQ(simulated->Info().num_scans, folder->Info().num_scans);
    EXPECT_EQ(simulated->Info().format, "sim");
    EXPECT_TRUE(simulated->Info().has_reference_poses);
    std::size_t scans = 0;
    while (auto expected = folder->Next()) {
        const auto scan = simulated->Next();
        ASSERT_TRUE(scan.has_value()) << "scan " << expected->index;
        EXPECT_EQ(scan->index, expected->index);
        ASSERT_EQ(scan->points.size(), expected->points.size()) << "scan " << expected->index;
        // Bit for bit: the folder holds the same float32 values.
        for (std::size_t i = 0; i < scan->points.size(); ++i) {
            ASSERT_EQ(scan->points[i], expected->points[i]) << "scan " << expected->index << " point " << i;
        }
        EXPECT_EQ(scan->intensities, expected->intensities);
        EXPECT_EQ(scan->sensor_label, expected->sensor_label);
        EXPECT_FALSE(scan->has_point_times());
        EXPECT_FALSE(scan->T_odom_sensor.has_value());
        // The values times.txt and poses.txt hold (9 decimals), to the bit.
        EXPECT_EQ(scan->timestamp, expected->timestamp);
        ASSERT_TRUE(scan->T_world_sensor && expected->T_world_sensor);
        EXPECT_TRUE(scan->T_world_sensor->matrix() == expected->T_world_sensor->matrix()) << "scan " << expected->index;
        ++scans;
    }
    EXPECT_EQ(scans, 5u);
    EXPECT_FALSE(simulated->Next().has_value());
}

TEST(SimReader, SkipToGivesTheScanReadingThroughWouldAndCountsThePassedOnes) {
    // --from on a simulated drive goes to its scan directly: each scan is ray-cast from its own pose.
    SimConfig config = SimPreset("tiny");
    config.max_scans = 6;
    auto through = OpenSimulation(config, "sim:tiny");
    std::optional<Scan> expected;
    for (int k = 0; k <= 4; ++k) expected = through->Next();
    ASSERT_TRUE(expected && expected->index == 4u);
    auto skipping = OpenSimulation(config, "sim:tiny");
    ASSERT_TRUE(skipping->SkipTo(4));
    EXPECT_EQ(skipping->Stats().scans, 4u);
    ASSERT_TRUE(skipping->SkipTo(2));  // already past: nothing moves
    const auto scan = skipping->Next();
    ASSERT_TRUE(scan);
    EXPECT_EQ(scan->index, 4u);
    EXPECT_TRUE(scan->points == expected->points);
    EXPECT_EQ(scan->timestamp, expected->timestamp);
    ASSERT_TRUE(scan->T_world_sensor && expected->T_world_sensor);
    EXPECT_TRUE(scan->T_world_sensor->matrix() == expected->T_world_sensor->matrix());
    EXPECT_EQ(skipping->Stats().scans, 5u);
    ASSERT_TRUE(skipping->SkipTo(100));  // past the end: the end
    EXPECT_FALSE(skipping->Next().has_value());
    EXPECT_EQ(skipping->Stats().scans, 6u);
}

TEST(SimReader, OpenDatasetReadsAPresetByNameAndNamesAnUnknownOne) {
    RegisterSimulatorDatasets();
    EXPECT_TRUE(IsSchemeDataset("sim:tiny"));
    EXPECT_FALSE(IsSchemeDataset("tiny"));
    EXPECT_EQ(DatasetName("sim:tiny"), "sim:tiny");  // never made absolute: `eval` opens it again
    auto reader = OpenDataset("sim:tiny");
    EXPECT_EQ(reader->Info().num_scans, PlanSimulation(SimPreset("tiny")).trajectory.size());
    const auto first = reader->Next();
    ASSERT_TRUE(first.has_value());
    EXPECT_GT(first->points.size(), 1000u);
    try {
        OpenDataset("sim:no-such-preset");
        FAIL() << "an unknown preset was accepted";
    } catch (const DatasetError& error) {
        EXPECT_NE(std::string(error.what()).find("sim:no-such-preset"), std::string::npos) << error.what();
        EXPECT_NE(std::string(error.what()).find("tiny"), std::string::npos) << "names the known presets: " << error.what();
    }
}

}  // namespace
}  // namespace revisit
