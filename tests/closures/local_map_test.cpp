#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <random>
#include <tbb/global_control.h>
#include <tuple>

#include "closures/density_image.hpp"
#include "closures/features.hpp"
#include "closures/ground_alignment.hpp"
#include "closures/local_map.hpp"
#include "core/se3.hpp"
#include "test_support.hpp"

namespace revisit {
namespace {

std::vector<Eigen::Isometry3d> Line(int n, double step) {
    std::vector<Eigen::Isometry3d> poses;
    for (int i = 0; i < n; ++i) poses.push_back(PoseFromXYZRPY(i * step, 0.0, 0.0, 0.0, 0.0, 0.0));
    return poses;
}

TEST(LocalMapper, SplitsByTravelAndRecordsRanges) {
    const std::vector<Eigen::Vector3f> scan = {{1.f, 0.f, 0.f}, {0.f, 3.f, 0.f}};
    LocalMapConfig config;
    config.split_distance = 10.0;
    const auto maps = BuildLocalMaps(std::vector<std::vector<Eigen::Vector3f>>(25, scan), Line(25, 1.0), config);
    // Travel 24 m: maps start at scans 0, 11, 22 (split once more than 10 m from the first pose).
    ASSERT_EQ(maps.size(), 3u);
    EXPECT_EQ(maps[0].first_scan, 0u);
    EXPECT_EQ(maps[0].last_scan, 10u);
    EXPECT_EQ(maps[1].first_scan, 11u);
    EXPECT_EQ(maps[2].last_scan, 24u);
    EXPECT_EQ(maps[1].id, 1);
    EXPECT_NEAR(maps[1].T_world_map.translation().x(), 11.0, 1e-12);
    EXPECT_EQ(maps[1].T_map_scan.size(), 11u);
    EXPECT_NEAR(maps[1].travel_start, 11.0, 1e-12);
    // Points are in the map frame: scan k's point (1, 0, 0) lands at x = k + 1 - 11.
    bool found = false;
    for (const auto& p : maps[1].points) found |= (p - Eigen::Vector3f(5.f, 0.f, 0.f)).norm() < 1e-5f;
    EXPECT_TRUE(found);
}

TEST(LocalMapper, VoxelCapAndCarryOver) {
    std::vector<Eigen::Vector3f> dense;
    for (int i = 0; i < 100; ++i) dense.emplace_back(0.5f + 0.001f * i, 0.5f, 0.5f);  // one voxel
    LocalMapConfig config;
    config.split_distance = 5.0;
    auto maps = BuildLocalMaps({dense, dense}, Line(2, 1.0), config);
    ASSERT_EQ(maps.size(), 1u);
    EXPECT_EQ(maps[0].points.size(), 40u);  // two voxels (the second scan is 1 m ahead), 20 points each

    config.carry_over = true;
    config.carry_radius = 50.0;
    maps = BuildLocalMaps(std::vector<std::vector<Eigen::Vector3f>>(4, dense), Line(4, 3.0), config);
    ASSERT_EQ(maps.size(), 2u);
    // The second map (scans 2-3, starting 6 m on) also holds the first map's points, 6 m behind it.
    bool carried = false;
    for (const auto& p : maps[1].points) carried |= p.x() < -4.f;
    EXPECT_TRUE(carried);
}

/// A 60 m walk around a 15 m square courtyard, back to its start, one pose every 0.5 m.
std::vector<Eigen::Isometry3d> Courtyard() {
    std::vector<Eigen::Isometry3d> poses;
    const Eigen::Vector2d corners[] = {{0, 0}, {15, 0}, {15, 15}, {0, 15}, {0, 0}};
    for (int side = 0; side < 4; ++side) {
        const Eigen::Vector2d direction = (corners[side + 1] - corners[side]) / 15.0;
        const double yaw = std::atan2(direction.y(), direction.x());
        for (int k = 0; k < 30; ++k) {
            const Eigen::Vector2d p = corners[side] + 0.5 * k * direction;
            poses.push_back(PoseFromXYZRPY(p.x(), p.y(), 0.0, 0.0, 0.0, yaw));
        }
    }
    poses.push_back(PoseFromXYZRPY(0.0, 0.0, 0.0, 0.0, 0.0, -M_PI / 2));
    return poses;
}

TEST(LocalMapper, ExtentCapSplitsACourtyardLoopSoTheReturnMeetsTheStart) {
    const auto poses = Courtyard();
    const std::vector<std::vector<Eigen::Vector3f>> scans(poses.size(), {{1.f, 0.f, 0.f}});
    LocalMapConfig config;  // paper split: 100 m of travel, more than the whole walk
    ASSERT_EQ(BuildLocalMaps(scans, poses, config).size(), 1u);

    config.max_extent = 10.0;
    const auto maps = BuildLocalMaps(scans, poses, config);
    ASSERT_GE(maps.size(), 4u);
    for (const auto& map : maps) {
        for (const auto& T_map_scan : map.T_map_scan) EXPECT_LE(T_map_scan.translation().norm(), 10.0 + 1e-9);
    }
    // The last map ends where the first began, and enough travel lies between them that a skip of
    // recent maps by 40 m of travel (configs/handheld.yaml) still compares them.
    const auto& first = maps.front();
    const auto& last = maps.back();
    EXPECT_EQ(last.last_scan, poses.size() - 1);
    EXPECT_LT((last.T_world_map * last.T_map_scan.back()).translation().norm(), 1e-9);
    EXPECT_GE(last.travel_start - first.travel_end, 40.0);

    // The travel split still applies inside the cap: a straight 30 m walk with a 100 m cap and 10 m split.
    config.max_extent = 100.0;
    config.split_distance = 10.0;
    EXPECT_EQ(BuildLocalMaps(std::vector<std::vector<Eigen::Vector3f>>(31, {{1.f, 0.f, 0.f}}), Line(31, 1.0), config).size(), 3u);
}

TEST(GroundAlignment, LevelsATiltedMap) {
    const auto world = test::MakeBoxWorld(5, 60.0, 30);
    auto map = test::SimulateLocalMap(world, test::StraightRoute(0.0, 0.0, 0.0), 0, 1);
    const auto T_tilted_map = PoseFromXYZRPY(0.0, 0.0, 0.0, 0.08, -0.12, 0.0);
    const auto tilted = test::Transformed(map, T_tilted_map, 0);
    const auto ground = AlignGround(tilted.points);
    ASSERT_TRUE(ground.aligned);
    // Levelled frame: ground (1.8 m below the sensor) at z = 0, up is +z again.
    const Eigen::Vector3d up = ground.T_ground_map.linear() * T_tilted_map.linear() * Eigen::Vector3d::UnitZ();
    EXPECT_LT(std::acos(up.z()), 0.3 * M_PI / 180.0);
    const Eigen::Vector3d ground_point = ground.T_ground_map * T_tilted_map * Eigen::Vector3d(10.0, 5.0, -1.8);
    EXPECT_NEAR(ground_point.z(), 0.0, 0.05);
}

TEST(DensityImage, NormalizationThresholdAndElevation) {
    std::vector<Eigen::Vector3f> points;
    for (int i = 0; i < 100; ++i) points.emplace_back(0.25f, 0.25f, 0.01f * i);  // dense cell (0, 0), up to 0.99 m
    for (int i = 0; i < 4; ++i) points.emplace_back(2.25f, 0.25f, 0.f);          // 4% of the max: removed
    for (int i = 0; i < 50; ++i) points.emplace_back(2.25f, 1.25f, 0.f);         // half the max
    DensityImageConfig config;
    config.resolution = 0.5;
    const auto image = ComputeDensityImage(points, config);
    ASSERT_EQ(image.image.cols, 5);
    ASSERT_EQ(image.image.rows, 3);
    EXPECT_EQ(image.image.at<std::uint8_t>(0, 0), 255);
    EXPECT_EQ(image.image.at<std::uint8_t>(0, 4), 0);
    EXPECT_EQ(image.image.at<std::uint8_t>(2, 4), 128);
    EXPECT_NEAR((image.ToMetric(4, 2) - Eigen::Vector2d(2.5, 1.5)).norm(), 0.0, 1e-6);
    // Paper-era code: 5% compared on the byte scale keeps the sparse cell.
    config.threshold = DensityThreshold::kByteScale;
    EXPECT_EQ(ComputeDensityImage(points, config).image.at<std::uint8_t>(0, 4), 10);
    config.elevation_instead = true;
    config.threshold = DensityThreshold::kFractionOfMax;
    const auto elevation = ComputeDensityImage(points, config);
    EXPECT_EQ(elevation.image.at<std::uint8_t>(0, 0), 255);  // highest cell
    EXPECT_EQ(elevation.image.at<std::uint8_t>(2, 4), 0);    // lowest occupied cell: below 5% of the range
}

TEST(Features, RobustScalingAndAdaptiveBudgetRaiseKeypointsOnSparseMaps) {
    // A small, sparse world (handheld scale): few points per cell.
    const auto world = test::MakeBoxWorld(8, 25.0, 25);
    auto map = test::SimulateLocalMap(world, test::StraightRoute(0.0, 0.0, 0.0, 5, 1.0), 0, 3, 20.0);
    std::mt19937 rng(1);
    std::vector<Eigen::Vector3f> sparse;
    for (const auto& p : map.points)
        if (rng() % 4 == 0) sparse.push_back(p);
    const auto paper = ComputeFeatures(ComputeDensityImage(sparse, {}).image, {});
    DensityImageConfig density;
    density.scaling = DensityScaling::kPercentile;
    density.target_extent_pixels = 400;
    density.min_resolution = 0.1;
    FeatureConfig features;
    features.min_keypoints = 150;
    features.pad_border = true;
    const auto robust = ComputeFeatures(ComputeDensityImage(sparse, density).image, features);
    EXPECT_GT(robust.keypoints.size(), 2 * paper.keypoints.size() + 20);
    EXPECT_EQ(robust.keypoints.size(), robust.descriptors.size());
}

}  // namespace
}  // namespace revisit

namespace revisit {
namespace {

/// Scans of 60,000 points around the origin (most voxels fill within a few scans).
std::vector<std::vector<Eigen::Vector3f>> DenseScans(int count) {
    std::mt19937 rng(11);
    std::normal_distribution<float> spread(0.0f, 6.0f);
    std::vector<std::vector<Eigen::Vector3f>> scans(count);
    for (auto& scan : scans)
        for (int i = 0; i < 60000; ++i) scan.emplace_back(spread(rng), spread(rng), 0.3f * spread(rng));
    return scans;
}

TEST(LocalMapper, KeepsTheFirstPointsOfEveryVoxelInInputOrderAtAnyThreadCount) {
    const auto scans = DenseScans(4);
    std::vector<Eigen::Isometry3d> poses;
    for (int i = 0; i < 4; ++i) poses.push_back(PoseFromXYZRPY(0.5 * i, 0.1 * i, 0, 0, 0, 0.05 * i));
    std::vector<std::vector<Eigen::Vector3f>> results;
    for (const int threads : {1, 2, 4}) {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, std::size_t(threads));
        results.push_back(BuildLocalMaps(scans, poses).at(0).points);
    }
    EXPECT_EQ(results[0], results[1]);
    EXPECT_EQ(results[0], results[2]);
    // The definition: per voxel, the first 20 points met, in order.
    std::map<std::tuple<int, int, int>, std::vector<Eigen::Vector3f>> expected;
    for (int s = 0; s < 4; ++s) {
        const Eigen::Isometry3f T = (poses[0].inverse() * poses[std::size_t(s)]).cast<float>();
        for (const auto& p : scans[std::size_t(s)]) {
            const Eigen::Vector3f q = T * p;
            const Eigen::Vector3i k = (q / 1.0f).array().floor().cast<int>();
            auto& voxel = expected[{k.x(), k.y(), k.z()}];
            if (voxel.size() < 20) voxel.push_back(q);
        }
    }
    std::map<std::tuple<int, int, int>, std::vector<Eigen::Vector3f>> got;
    for (const auto& q : results[0]) {
        const Eigen::Vector3i k = (q / 1.0f).array().floor().cast<int>();
        got[{k.x(), k.y(), k.z()}].push_back(q);
    }
    EXPECT_EQ(got, expected);
}

}  // namespace
}  // namespace revisit
