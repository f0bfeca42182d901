/// Issue 14: settings derived from the data. Different worlds give different, documented settings;
/// explicit values win; a 2D laser's wrong stated aperture is measured and corrected.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "closures/ground_alignment.hpp"
#include "io/reader.hpp"
#include "io/writer.hpp"
#include "settings/auto_settings.hpp"
#include "settings/data_profile.hpp"
#include "sim/presets.hpp"
#include "sim/simulate.hpp"
#include "test_data.hpp"

namespace revisit {
namespace {
namespace fs = std::filesystem;

/// The first `scans` scans of a simulator preset, written to `out` (a KITTI folder or a rawlog).
fs::path Simulate(const std::string& preset, std::size_t scans, const fs::path& out) {
    SimConfig config = SimPreset(preset);
    config.max_scans = scans;
    RunSimulation(config, out, true);
    return out;
}

double Chosen(const AutoSettings& settings, const std::string& key) {
    for (const auto& c : settings.choices) {
        if (c.key == key) return c.value;
    }
    ADD_FAILURE() << "no choice for " << key;
    return -1.0;
}

std::string DescribeAll(std::initializer_list<const AutoSettings*> settings) {
    std::string text;
    for (const auto* s : settings) {
        for (const auto& line : s->profile.Describe()) text += line + "\n";
        for (const auto& line : s->Describe()) text += line + "\n";
    }
    return text;
}

TEST(AutoSettings, AWalkACityDriveAndAnIndoorLaserGetDifferentDocumentedSettings) {
    test::TempDir dir;
    PipelineConfig walk, city, indoor;
    // Enough scans for the speed to settle (the car starts from rest).
    const auto walk_settings = ConfigureFromData(walk, Simulate("campus-handheld", 60, dir / "walk"));
    const auto city_settings = ConfigureFromData(city, Simulate("tiny", 150, dir / "city"));
    const auto indoor_settings = ConfigureFromData(indoor, Simulate("indoor-2d-180", 12, dir / "indoor.rawlog"));

    // The indoor laser is planar with centimetre voxels; the walk's scene is smaller than the city's.
    EXPECT_TRUE(indoor.odometry.planar);
    EXPECT_FALSE(city.odometry.planar);
    EXPECT_FALSE(walk.odometry.planar);
    EXPECT_LT(indoor.odometry.voxel_size, walk.odometry.voxel_size);
    EXPECT_LT(walk.odometry.voxel_size, city.odometry.voxel_size) << DescribeAll({&walk_settings, &city_settings});
    EXPECT_LT(indoor.odometry.max_range, city.odometry.max_range);
    EXPECT_LT(walk.odometry.min_range, 5.0);  // the paper-era 5 m would drop the walk's near scene
    // Issue 19: the second ICP from the translation-only guess is for the swaying hand, not the car.
    EXPECT_TRUE(walk.odometry.turn_hypothesis) << DescribeAll({&walk_settings});
    EXPECT_FALSE(city.odometry.turn_hypothesis) << DescribeAll({&city_settings});
    // What was applied is what was chosen, and each choice says why.
    for (const auto* s : {&walk_settings, &city_settings, &indoor_settings}) {
        ASSERT_FALSE(s->choices.empty());
        for (const auto& c : s->choices) {
            EXPECT_TRUE(c.applied) << c.key;
            EXPECT_FALSE(c.reason.empty()) << c.key;
        }
    }
    EXPECT_DOUBLE_EQ(city.odometry.voxel_size, Chosen(city_settings, "odometry.voxel_size"));
    EXPECT_DOUBLE_EQ(city.odometry.initial_threshold, 2.0 * city.odometry.voxel_size);
    EXPECT_NE(DumpConfig(walk), DumpConfig(city));

    // Issue 16: the closure detector's scale follows the data too. The walk (1.4 m/s) gets maps of
    // about 10 s of motion, the drive the paper's 100 m; pixels follow the map voxel.
    EXPECT_LT(walk.local_map.split_distance, 25.0) << DescribeAll({&walk_settings});
    EXPECT_DOUBLE_EQ(city.local_map.split_distance, 100.0) << DescribeAll({&city_settings});
    EXPECT_LT(walk.detector.density.resolution, city.detector.density.resolution);
    EXPECT_TRUE(walk.detector.align_ground);
    EXPECT_DOUBLE_EQ(indoor.graph_noise.odometry_rotation_per_m, 0.002);
    EXPECT_DOUBLE_EQ(indoor.detector.density.resolution, indoor.odometry.voxel_size);
}

/// A scan of a sensor at the centre of a cylinder of radius 20 m: `beams` beams per azimuth step of
/// 0.2 deg (azimuth-major, as a spinning sensor fires), beam k at `elevation_deg(azimuth, k)`.
template <typename Elevation>
Scan RingScan(int beams, const Elevation& elevation_deg, std::size_t index) {
    Scan scan;
    scan.index = index;
    scan.timestamp = 0.1 * static_cast<double>(index);
    for (double azimuth = 0.0; azimuth < 360.0; azimuth += 0.2) {
        for (int k = 0; k < beams; ++k) {
            const double a = azimuth * M_PI / 180.0, e = elevation_deg(azimuth, k) * M_PI / 180.0;
            scan.points.emplace_back(Eigen::Vector3f(20.0f * std::cos(a), 20.0f * std::sin(a), 20.0f * std::tan(e)));
        }
    }
    return scan;
}

std::string ChosenText(const std::vector<SettingChoice>& choices, const std::string& key) {
    for (const auto& c : choices) {
        if (c.key == key) return c.text + " <- " + c.reason;
    }
    return "no choice for " + key;
}

TEST(AutoSettings, RingsADegreeOrMoreApartGetPointToPlaneRegistration) {
    auto profile = [](int beams, const auto& elevation) {
        DataProfiler profiler(3);
        for (std::size_t i = 0; i < 3; ++i) profiler.Add(RingScan(beams, elevation, i));
        return profiler.Profile();
    };
    const DataProfile sparse = profile(16, [](double, int k) { return -15.0 + 2.0 * k; });  // VLP-16
    // HDL-64 (64 beams per azimuth: a sample of every 28th point would see only every 4th ring).
    const DataProfile dense = profile(64, [](double, int k) { return -24.8 + 0.42 * k; });
    // A rosette: each beam sweeps the elevations as it turns.
    const DataProfile none = profile(6, [](double azimuth, int k) { return -35.0 + 70.0 * std::fmod(0.618034 * k + 0.0371 * azimuth, 1.0); });
    EXPECT_EQ(sparse.rings, 16);
    EXPECT_NEAR(sparse.ring_spacing_deg, 2.0, 0.1);
    EXPECT_GE(dense.rings, 60);  // the outermost rings may fall outside the 1-99% elevation span
    EXPECT_NEAR(dense.ring_spacing_deg, 0.42, 0.02);
    EXPECT_EQ(none.rings, 0);
    EXPECT_EQ(ChosenText(ChooseSettings(sparse, std::nullopt, std::nullopt), "odometry.residual"),
              "point_to_plane <- 16 rings 2 deg apart: sparse on walls");
    EXPECT_EQ(ChosenText(ChooseSettings(dense, std::nullopt, std::nullopt), "odometry.residual"),
              "point_to_point <- " + std::to_string(dense.rings) + " rings 0.42 deg apart");
    EXPECT_EQ(ChosenText(ChooseSettings(none, std::nullopt, std::nullopt), "odometry.residual"),
              "point_to_point <- no distinct rings");
}

TEST(AutoSettings, FarPointsKeepTheProfileSmallAndAreNamedWithTheirScan) {
    // A VLP-16-like scan over flat ground with every 20th point thrown out to `far` metres: the
    // ground grid spanned the points' bounding box (1e5 m at 1 m cells: 4e10 cells, bad_alloc).
    const auto far_scan = [](std::size_t index, float far) {
        Scan scan = RingScan(16, [](double, int k) { return -15.0 + 2.0 * k; }, index);
        for (auto& p : scan.points) p.z() = std::max(p.z(), -1.7f);  // the lower rings hit the ground
        for (std::size_t i = 0; i < scan.points.size(); i += 20) scan.points[i].head<2>() *= far / 20.0f;
        return scan;
    };
    for (const float far : {3e4f, 1e5f, 1e30f}) {
        DataProfiler profiler(3);
        profiler.Add(RingScan(16, [](double, int k) { return -15.0 + 2.0 * k; }, 0));
        profiler.Add(far_scan(7, far));
        profiler.Add(far_scan(8, far));
        const DataProfile profile = profiler.Profile();
        EXPECT_EQ(profile.far_scan, 7u) << far;
        EXPECT_NEAR(profile.far_range / far, 1.0, 0.01) << far;
        EXPECT_LT(profile.range_p50, 30.0);  // the median is the scene's
        PipelineConfig config;
        const AutoSettings settings = ApplyAutoSettings(config, profile);
        bool named = false;
        for (const auto& w : settings.warnings) named = named || w.rfind("scan 7 has a point ", 0) == 0;
        EXPECT_TRUE(named) << far;
        EXPECT_LE(config.odometry.max_range, 300.0);
    }
}

TEST(GroundAlignment, FarPointsDoNotChangeTheGroundFound) {
    // Ground at z = -1.5 tilted 5 degrees about x, 20 m across, plus one point per metre far away.
    const double tilt = 5.0 * M_PI / 180.0;
    std::vector<Eigen::Vector3f> points;
    for (int x = -10; x <= 10; ++x) {
        for (int y = -10; y <= 10; ++y) points.emplace_back(float(x) + 0.3f, float(y) + 0.3f, float(-1.5 + std::tan(tilt) * y));
    }
    const GroundAlignment near = AlignGround(points);
    for (const float far : {3e4f, 1e5f, 3e38f}) {
        std::vector<Eigen::Vector3f> with_far = points;
        for (int k = 0; k < 20; ++k) with_far.emplace_back(far - float(k), far, 50.0f);
        with_far.emplace_back(std::numeric_limits<float>::quiet_NaN(), 0.0f, 0.0f);
        const GroundAlignment result = AlignGround(with_far);
        ASSERT_TRUE(result.aligned) << far;
        EXPECT_EQ(result.num_ground_points, near.num_ground_points) << far;
        EXPECT_TRUE(result.T_ground_map.isApprox(near.T_ground_map, 1e-9)) << far;
    }
}

TEST(AutoSettings, ExplicitValuesWinAndContradictedOnesAreWarnedAbout) {
    test::TempDir dir;
    const fs::path data = Simulate("indoor-2d-180", 12, dir / "indoor.rawlog");
    PipelineConfig config =
        LoadConfig({}, {"odometry.voxel_size=0.7", "odometry.max_range=100", "local_map.split_distance=42"});
    const auto settings = ConfigureFromData(config, data);
    EXPECT_DOUBLE_EQ(config.odometry.voxel_size, 0.7);
    EXPECT_DOUBLE_EQ(config.local_map.split_distance, 42.0);  // the closure detector's settings too
    EXPECT_DOUBLE_EQ(config.detector.skip_recent_travel, 84.0);  // and what scales with it follows it
    EXPECT_DOUBLE_EQ(config.detector.density.resolution, Chosen(settings, "density.resolution"));
    EXPECT_DOUBLE_EQ(config.odometry.max_range, 100.0);
    EXPECT_TRUE(config.odometry.planar);  // not given: still derived
    bool warned_range = false;
    for (const auto& w : settings.warnings) warned_range = warned_range || w.find("odometry.max_range = 100") != std::string::npos;
    EXPECT_TRUE(warned_range) << "a 100 m range on a scene within a few metres is worth a warning";
    for (const auto& c : settings.choices) {
        if (c.key == "odometry.voxel_size") {
            EXPECT_FALSE(c.applied);
        }
    }
    // Off: nothing derived.
    PipelineConfig off = LoadConfig({}, {"input.auto_settings=false"});
    EXPECT_TRUE(ConfigureFromData(off, data).choices.empty());
    EXPECT_FALSE(off.odometry.planar);
}

/// intel.rawlog's first scans: 166 beams, 1.41 m median range, and fewer than the 150 points a 2D scan
/// should keep at any voxel.
DataProfile IntelsFirstScans() {
    DataProfile sparse;
    sparse.scans = 10;
    sparse.planar = true;
    sparse.points_per_scan = 166;
    sparse.range_p50 = 1.41;
    sparse.range_p95 = 7.6;
    sparse.range_p99 = 9.0;
    sparse.voxel_candidates = VoxelCandidates();
    sparse.source_points = {87, 62, 45, 36, 30, 26, 20, 17, 14, 11, 9};
    return sparse;
}

TEST(AutoSettings, ASparse2DLaserKeepsTheSceneScaleVoxel) {
    // The floor of 150 points cannot bind: the scale rule (not rounded up) decides.
    const DataProfile sparse = IntelsFirstScans();
    auto voxel = [](const std::vector<SettingChoice>& choices) {
        for (const auto& c : choices)
            if (c.key == "odometry.voxel_size") return c.value;
        return -1.0;
    };
    EXPECT_DOUBLE_EQ(voxel(ChooseSettings(sparse, std::nullopt)), 0.1);
    // A denser laser (fr079: 200 points at the finest voxel, fewer above) is still held by the floor.
    DataProfile dense = sparse;
    dense.range_p50 = 2.43;
    dense.source_points = {200, 140, 100, 80, 60, 50, 40, 30, 25, 20, 15};
    EXPECT_DOUBLE_EQ(voxel(ChooseSettings(dense, std::nullopt)), 0.05);
}

TEST(AutoSettings, ASparse2DLaserWithoutOdometryNeedsCorrespondencesForAFifthOfItsPoints) {
    // 62 points a scan registered at the 0.1 m voxel its scale gives (intel's first scans): the ICP's
    // floor of 20 correspondences would be a third of them.
    const DataProfile sparse = IntelsFirstScans();
    const auto floor = [](const DataProfile& profile) {
        for (const auto& c : ChooseSettings(profile, std::nullopt))
            if (c.key == "odometry.min_correspondences") return c.value;
        return -1.0;  // not chosen: the default holds
    };
    EXPECT_DOUBLE_EQ(floor(sparse), 12.0);
    // With wheel odometry a frame the ICP cannot register keeps the wheels' motion: the floor stays.
    DataProfile wheeled = sparse;
    wheeled.has_odometry_prior = true;
    EXPECT_EQ(floor(wheeled), -1.0);
    // A laser that keeps 200 points at its voxel: 20 is a tenth of them.
    DataProfile dense = sparse;
    dense.range_p50 = 2.43;
    dense.source_points = {200, 140, 100, 80, 60, 50, 40, 30, 25, 20, 15};
    EXPECT_EQ(floor(dense), -1.0);
    // Never below twice a planar pose's three unknowns.
    DataProfile sparsest = sparse;
    sparsest.source_points = {20, 12, 9, 7, 6, 5, 4, 4, 3, 3, 3};
    EXPECT_DOUBLE_EQ(floor(sparsest), 6.0);
}

/// Rewrites a simulated 2D rawlog stating `stated_deg` for its 180-degree beams.
fs::path WithStatedAperture(const fs::path& source, double stated_deg, const fs::path& out) {
    auto reader = OpenDataset(source);
    WriterOptions options;
    options.planar_as_range_scan = true;
    options.planar_beams = 361;
    options.planar_aperture = M_PI;
    options.planar_stated_aperture = stated_deg * M_PI / 180.0;
    auto writer = CreateRawlogWriter(out, options, true);
    while (auto scan = reader->Next()) writer->Write(*scan);
    writer->Finish();
    return out;
}

TEST(ApertureCheck, AStatedApertureTheTurnsContradictIsCorrectedWithAWarningAndARightOneIsKept) {
    test::TempDir dir;
    const fs::path truth = Simulate("indoor-2d-180", 1500, dir / "indoor.rawlog");

    PipelineConfig wrong;
    const auto corrected = ConfigureFromData(wrong, WithStatedAperture(truth, 90.0, dir / "wrong.rawlog"));
    ASSERT_TRUE(corrected.aperture) << "no measurable turns found";
    EXPECT_TRUE(corrected.aperture->contradicts) << corrected.aperture->Describe();
    EXPECT_NEAR(wrong.input.laser_aperture_deg, 180.0, 1e-9) << corrected.aperture->Describe();
    ASSERT_FALSE(corrected.warnings.empty());
    EXPECT_NE(corrected.warnings.back().find("aperture corrected from 90 to 180 deg"), std::string::npos) << corrected.warnings.back();

    PipelineConfig right;
    const auto kept = ConfigureFromData(right, truth);
    ASSERT_TRUE(kept.aperture);
    EXPECT_FALSE(kept.aperture->contradicts) << kept.aperture->Describe();
    EXPECT_EQ(right.input.laser_aperture_deg, 0.0);
    EXPECT_TRUE(kept.warnings.empty());
}

}  // namespace
}  // namespace revisit
