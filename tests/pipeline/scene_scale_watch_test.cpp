/// The odometry's crop radius widens with the scene's scale as a sequence unfolds (issue 14), and
/// stays put while the scene does.
#include <gtest/gtest.h>

#include <cmath>
#include <tbb/global_control.h>

#include "core/error.hpp"
#include "io/reader.hpp"
#include "odometry/lidar_odometry.hpp"
#include "settings/auto_settings.hpp"
#include "pipeline/odometry_stages.hpp"
#include "settings/scene_scale_watch.hpp"
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

PipelineConfig AutoConfig(double max_range, double voxel = 1.0) {
    PipelineConfig config;
    config.odometry.max_range = max_range;
    config.odometry.voxel_size = voxel;
    return config;
}

TEST(SceneScaleWatch, WidensAtOnceWhenTheSceneOpensAndKeepsItWhenTheSceneCloses) {
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
    // Back in the courtyard: the crop stays wide (the square may come back into view).
    for (; position < 600; ++position) EXPECT_FALSE(watch.Add(position, Courtyard(12.0, position))) << position;
    EXPECT_DOUBLE_EQ(watch.max_range(), 100.0);
    // A little wider is not worth a change; and 1 m voxels support no more than 100 m (KISS-ICP's ratio).
    for (; position < 700; ++position) EXPECT_FALSE(watch.Add(position, Courtyard(80.0, position))) << position;
    for (; position < 800; ++position) EXPECT_FALSE(watch.Add(position, Courtyard(150.0, position))) << position;
}

TEST(SceneScaleWatch, WidensUpToAHundredMapVoxels) {
    // 0.1 m voxels (a 2D laser indoors): a 30 m crop already exceeds 100 voxels, so nothing widens;
    // 0.5 m voxels: up to 50 m however far the scene reaches.
    SceneScaleWatch fine(AutoConfig(30.0, 0.1)), coarse(AutoConfig(30.0, 0.5));
    std::optional<SettingUpdate> widened;
    for (std::size_t i = 0; i < 100; ++i) {
        EXPECT_FALSE(fine.Add(i, Courtyard(60.0, i))) << i;
        if (auto update = coarse.Add(i, Courtyard(60.0, i))) widened = update;
    }
    ASSERT_TRUE(widened);
    EXPECT_DOUBLE_EQ(widened->to, 50.0);
}

TEST(SceneScaleWatch, ARangeFromWiderFirstScansIsNeverNarrowed) {
    SceneScaleWatch watch(AutoConfig(90.0));
    for (std::size_t position = 0; position < 400; ++position) EXPECT_FALSE(watch.Add(position, Courtyard(12.0, position))) << position;
    EXPECT_DOUBLE_EQ(watch.max_range(), 90.0);
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

TEST(SceneScaleWatch, TheOdometryStagesMakeTheChangeAfterTheScanThatAskedForIt) {
    // Scans 0-59 in the courtyard, then the square: the window ending at scan 99 widens the crop.
    std::vector<Scan> scans;
    for (std::size_t i = 0; i < 120; ++i) scans.push_back(Courtyard(i < 60 ? 12.0 : 60.0, i));
    PipelineConfig config = AutoConfig(30.0);
    config.odometry.min_range = 0.5;  // every point of the ground too
    OdometryStages stages(config);
    std::vector<std::size_t> cropped;
    std::vector<std::size_t> updated_after;
    {
        const tbb::global_control two(tbb::global_control::max_allowed_parallelism, 2);
        RunOdometryStages(stages, scans, [&](OdometryStages::Item& item, const Eigen::Isometry3d&) {
            cropped.push_back(stages.odometry().LastStats().cropped_points);
            if (item.update) updated_after.push_back(item.position);
        });
    }
    ASSERT_EQ(updated_after, std::vector<std::size_t>{99});
    EXPECT_DOUBLE_EQ(stages.odometry().config().max_range, 100.0);
    ASSERT_EQ(cropped.size(), 120u);
    EXPECT_LT(cropped[99], 11520u - 3000u);  // the wall at 60 m was cropped up to the change ...
    EXPECT_EQ(cropped[100], 11520u);         // ... and is registered from the next scan on
}

TEST(LidarOdometry, AScanPreparedBeforeTheRangeChangedIsPreparedAgain) {
    OdometryConfig config;
    config.max_range = 30.0;
    config.min_range = 0.5;
    config.voxel_size = 1.0;
    LidarOdometry loop(config), ahead(config);
    const Scan first = Courtyard(50.0, 0), second = Courtyard(50.0, 1);
    PreparedScan first_prepared = PrepareScan(first, config), second_prepared = PrepareScan(second, config);
    loop.RegisterScan(first);
    ahead.RegisterPrepared(first, std::move(first_prepared));
    loop.SetMaxRange(80.0);
    ahead.SetMaxRange(80.0);
    ASSERT_FALSE(second_prepared.PreparedFor(ahead.config()));
    const Eigen::Isometry3d T_loop = loop.RegisterScan(second);
    const Eigen::Isometry3d T_ahead = ahead.RegisterPrepared(second, std::move(second_prepared));
    EXPECT_EQ(ahead.LastStats().cropped_points, 11520u);
    EXPECT_EQ(ahead.LastStats().cropped_points, loop.LastStats().cropped_points);
    EXPECT_EQ(ahead.LastStats().source_points, loop.LastStats().source_points);
    EXPECT_TRUE(T_ahead.isApprox(T_loop, 0.0)) << T_ahead.matrix() << "\n" << T_loop.matrix();
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
