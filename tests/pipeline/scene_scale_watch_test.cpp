/// The odometry's crop radius follows the scene's scale as a sequence unfolds (issue 14), and stays
/// put while the scene does.
#include <gtest/gtest.h>

#include <cmath>

#include "core/error.hpp"
#include "io/reader.hpp"
#include "odometry/lidar_odometry.hpp"
#include "pipeline/auto_settings.hpp"
#include "pipeline/scene_scale_watch.hpp"
#include "support/test_data.hpp"

namespace revisit {
namespace {

/// A 32-ring sensor 1.5 m above a flat ground, inside a round courtyard whose wall stands at `radius`:
/// rings below the horizon hit the ground (or the wall, if it is nearer), the others the wall.
Scan Courtyard(double radius, std::size_t index) {
    Scan scan;
    scan.index = index;
    scan.timestamp = 0.1 * static_cast<double>(index);
    for (int ring = 0; ring < 32; ++ring) {
        const double elevation = (-25.0 + 1.0 * ring) * M_PI / 180.0;
        for (int a = 0; a < 360; ++a) {
            const double azimuth = a * M_PI / 180.0;
            double range = radius / std::cos(elevation);
            if (elevation < 0.0) range = std::min(range, 1.5 / std::sin(-elevation));
            scan.points.emplace_back(static_cast<float>(range * std::cos(elevation) * std::cos(azimuth)),
                                     static_cast<float>(range * std::cos(elevation) * std::sin(azimuth)),
                                     static_cast<float>(range * std::sin(elevation)));
        }
    }
    return scan;
}

PipelineConfig AutoConfig(double max_range) {
    PipelineConfig config;
    config.odometry.max_range = max_range;
    return config;
}

TEST(SceneScaleWatch, WidensAtOnceWhenTheSceneOpensAndNarrowsOnlyAfterItStaysSmall) {
    SceneScaleWatch watch(AutoConfig(30.0));
    ASSERT_TRUE(watch.active());
    std::size_t position = 0;
    for (; position < 150; ++position) EXPECT_FALSE(watch.Add(position, Courtyard(12.0, position))) << position;
    // The courtyard opens onto a 60 m square: the first window that sees it widens the crop.
    std::optional<SettingUpdate> widened;
    for (; position < 200 && !widened; ++position) widened = watch.Add(position, Courtyard(60.0, position));
    ASSERT_TRUE(widened);
    EXPECT_EQ(widened->scan, 200u);
    EXPECT_EQ(widened->key, "odometry.max_range");
    EXPECT_DOUBLE_EQ(widened->from, 30.0);
    EXPECT_DOUBLE_EQ(widened->to, MaxRangeFor(60.0 / std::cos(6.0 * M_PI / 180.0)));
    EXPECT_NE(DescribeUpdate(*widened).find("scan 200: odometry.max_range 30 -> 100"), std::string::npos) << DescribeUpdate(*widened);
    // Back in the courtyard: kept for three windows (a passing occlusion is not a smaller scene) ...
    for (; position < 350; ++position) EXPECT_FALSE(watch.Add(position, Courtyard(12.0, position))) << position;
    // ... and narrowed once the last four windows all saw the small scene.
    std::optional<SettingUpdate> narrowed;
    for (; position < 400 && !narrowed; ++position) narrowed = watch.Add(position, Courtyard(12.0, position));
    ASSERT_TRUE(narrowed);
    EXPECT_EQ(narrowed->scan, 400u);
    EXPECT_DOUBLE_EQ(narrowed->to, 30.0);
    EXPECT_DOUBLE_EQ(watch.max_range(), 30.0);
}

TEST(SceneScaleWatch, ARangeFromTheFirstScansIsNarrowedOnlyAfterFourWindows) {
    // The first scans looked farther (90 m) than the next ones: a gap in the scene's first windows
    // (passing a wall, a crowd around the sensor) must not narrow it.
    SceneScaleWatch watch(AutoConfig(90.0));
    std::size_t position = 0;
    for (; position < 199; ++position) EXPECT_FALSE(watch.Add(position, Courtyard(12.0, position))) << position;
    const auto narrowed = watch.Add(position, Courtyard(12.0, position));
    ASSERT_TRUE(narrowed);
    EXPECT_EQ(narrowed->scan, 200u);
    EXPECT_DOUBLE_EQ(narrowed->to, 30.0);
}

TEST(SceneScaleWatch, AGivenRangeOrFixedSettingsAreNeverChanged) {
    PipelineConfig given = AutoConfig(30.0);
    given.explicit_keys.insert("odometry.max_range");
    PipelineConfig off = AutoConfig(30.0);
    off.input.follow_scene_scale = false;
    PipelineConfig no_auto = AutoConfig(30.0);
    no_auto.input.auto_settings = false;
    for (const auto& config : {given, off, no_auto}) {
        SceneScaleWatch watch(config);
        EXPECT_FALSE(watch.active());
        for (std::size_t i = 0; i < 100; ++i) EXPECT_FALSE(watch.Add(i, Courtyard(60.0, i)));
    }
}

TEST(SceneScaleWatch, EmptyScansSayNothingAboutTheScene) {
    SceneScaleWatch watch(AutoConfig(30.0));
    for (std::size_t i = 0; i < 300; ++i) EXPECT_FALSE(watch.Add(i, Scan{})) << i;
}

/// Real sequences whose scene keeps its scale keep the range chosen from their first scans.
TEST(SceneScaleWatch, RealWalkAndDriveKeepTheirStartingRange) {
    for (const char* name : {"livox_handheld_walk", "kitti00_first16"}) {
        const auto dataset = test::SharedData(name);
        REVISIT_REQUIRE_DATA(dataset);
        PipelineConfig config;
        ConfigureFromData(config, dataset);
        SceneScaleWatch watch(config);
        ASSERT_TRUE(watch.active());
        std::size_t position = 0;
        for (int pass = 0; pass < (std::string(name) == "kitti00_first16" ? 10 : 1); ++pass) {  // 160 KITTI scans
            auto reader = OpenDataset(dataset, MakeReaderOptions(config.input));
            while (auto scan = reader->Next()) EXPECT_FALSE(watch.Add(position++, *scan)) << name << " scan " << position;
        }
        EXPECT_GE(position, 160u);
    }
}

TEST(LidarOdometry, SetMaxRangeWidensTheCropFromTheNextScan) {
    OdometryConfig config;
    config.max_range = 30.0;
    config.min_range = 0.5;
    config.voxel_size = 1.0;
    LidarOdometry odometry(config);
    odometry.RegisterScan(Courtyard(50.0, 0));
    const std::size_t cropped_at_30 = odometry.LastStats().cropped_points;
    odometry.SetMaxRange(80.0);
    odometry.RegisterScan(Courtyard(50.0, 1));
    EXPECT_LT(cropped_at_30, 11520u - 3000u);                   // the wall at 50 m was cropped ...
    EXPECT_EQ(odometry.LastStats().cropped_points, 11520u);     // ... and is now registered
    EXPECT_DOUBLE_EQ(odometry.config().max_range, 80.0);
    EXPECT_DOUBLE_EQ(odometry.config().VoxelSize(), 1.0);
    EXPECT_THROW(odometry.SetMaxRange(0.2), ConfigError);
}

}  // namespace
}  // namespace revisit
