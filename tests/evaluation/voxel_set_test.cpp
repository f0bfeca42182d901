#include "evaluation/voxel_set.hpp"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iterator>
#include <random>
#include <set>
#include <vector>

namespace revisit {
namespace {

/// The voxel keys written out plainly, one per point: floor(coordinate / size) per axis, 21 bits
/// each around an offset; with subsample > 1 only keys whose SplitMix64 hash is 0 modulo it.
std::set<std::uint64_t> ReferenceKeys(const std::vector<std::pair<Eigen::Isometry3d, std::vector<Eigen::Vector3f>>>& scans,
                                      double voxel_size, std::size_t subsample) {
    std::set<std::uint64_t> keys;
    for (const auto& [pose, points] : scans) {
        for (const Eigen::Vector3f& p : points) {
            const Eigen::Vector3d w = pose * p.cast<double>();
            std::uint64_t key = 0;
            for (int axis = 0; axis < 3; ++axis) {
                const auto index = static_cast<std::int64_t>(std::floor(w[axis] / voxel_size)) + (1 << 20);
                key = (key << 21) | (static_cast<std::uint64_t>(index) & ((1ULL << 21) - 1));
            }
            std::uint64_t h = key;
            h ^= h >> 30;
            h *= 0xBF58476D1CE4E5B9ULL;
            h ^= h >> 27;
            h *= 0x94D049BB133111EBULL;
            h ^= h >> 31;
            if (subsample > 1 && h % subsample != 0) continue;
            keys.insert(key);
        }
    }
    return keys;
}

/// A scan around `centre`: a lidar-like mix of random points, points on voxel and block faces
/// (exact multiples of the size, both signs) and their float neighbours.
std::vector<Eigen::Vector3f> Cloud(std::mt19937& rng, float extent, double voxel_size) {
    std::uniform_real_distribution<float> uniform(-extent, extent);
    std::uniform_int_distribution<int> cells(-40, 40);
    std::vector<Eigen::Vector3f> points;
    for (int k = 0; k < 20000; ++k) points.emplace_back(uniform(rng), uniform(rng), uniform(rng) / 8);
    for (int k = 0; k < 5000; ++k) {
        Eigen::Vector3f p(static_cast<float>(cells(rng) * voxel_size), static_cast<float>(cells(rng) * voxel_size),
                          static_cast<float>(cells(rng) * voxel_size));
        const int step = k % 3 - 1;  // below, on, above
        for (int axis = 0; axis < 3; ++axis)
            if (step != 0) p[axis] = std::nextafter(p[axis], step * 1e9f);
        points.push_back(p);
    }
    points.emplace_back(-0.0f, 0.0f, -0.0f);
    return points;
}

TEST(PackedVoxels, SameVoxelsAndOverlapsAsOneKeyPerVoxel) {
    std::mt19937 rng(3);
    // A power of two (multiplied by its reciprocal) and sizes that are not (divided); near the origin and
    // beyond +-524 km at 0.5 m, where the 21-bit axes wrap.
    for (const double voxel_size : {0.5, 0.3, 1.0, 0.1}) {
        for (const Eigen::Vector3d& origin : {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(-12.3, 40.0, -1.0),
                                             Eigen::Vector3d(524287.0 * voxel_size, -524288.0 * voxel_size, 3.0)}) {
            for (const std::size_t subsample : {std::size_t{1}, std::size_t{3}}) {
                std::vector<std::pair<Eigen::Isometry3d, std::vector<Eigen::Vector3f>>> a, b;
                for (int scan = 0; scan < 3; ++scan) {
                    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
                    pose.translation() = origin + Eigen::Vector3d(scan * 1.7, -scan * 0.9, 0.0);
                    pose.linear() = Eigen::AngleAxisd(0.3 * scan, Eigen::Vector3d::UnitZ()).toRotationMatrix();
                    a.emplace_back(pose, Cloud(rng, 30.0f, voxel_size));
                    pose.translation() += Eigen::Vector3d(5.0, 2.0, 0.0);
                    b.emplace_back(pose, Cloud(rng, 30.0f, voxel_size));
                }
                PackedVoxels packed_a, packed_b;
                for (const auto& [pose, points] : a) AddVoxels(packed_a, pose, points, voxel_size, subsample);
                for (const auto& [pose, points] : b) AddVoxels(packed_b, pose, points, voxel_size, subsample);
                const auto keys_a = ReferenceKeys(a, voxel_size, subsample), keys_b = ReferenceKeys(b, voxel_size, subsample);
                ASSERT_EQ(packed_a.size, keys_a.size());
                ASSERT_EQ(packed_b.size, keys_b.size());
                std::vector<std::uint64_t> common;
                std::set_intersection(keys_a.begin(), keys_a.end(), keys_b.begin(), keys_b.end(), std::back_inserter(common));
                ASSERT_GT(common.size(), 0u);
                const double expected = static_cast<double>(common.size()) / static_cast<double>(std::min(keys_a.size(), keys_b.size()));
                EXPECT_EQ(OverlapCoefficient(packed_a, packed_b), expected) << voxel_size << " m, subsample " << subsample;
                EXPECT_EQ(OverlapCoefficient(packed_b, packed_a), expected);
                EXPECT_EQ(OverlapCoefficient(packed_a, packed_a), 1.0);
                // Stopping early decides "above the threshold or not" as the full count does, at the
                // boundary too, and gives the exact overlap whenever it is above.
                for (const double threshold : {0.0, 0.1, 0.5, 0.9, expected, std::nextafter(expected, 0.0),
                                               std::nextafter(expected, 1.0)}) {
                    const double above = OverlapCoefficientAbove(packed_a, packed_b, threshold);
                    if (expected > threshold) {
                        EXPECT_EQ(above, expected) << threshold;
                    } else {
                        EXPECT_LE(above, threshold);
                    }
                    EXPECT_EQ(OverlapCoefficientAbove(packed_b, packed_a, threshold) > threshold, expected > threshold);
                }
            }
        }
    }
    EXPECT_EQ(OverlapCoefficient(PackedVoxels{}, PackedVoxels{}), 0.0);
}

TEST(VoxelColumns, BoundTheCommonVoxelsAndProveFarViewsApart) {
    // Pairs of scans 0 to 80 m apart (a car's views of one street): the columns' bound is never below the
    // voxels the sets share, equals it for a set with itself, and for views far apart proves what the merge
    // would find (the share stays below the ground truth's 0.5).
    std::mt19937 rng(7);
    const auto scan_at = [&](double x, double y) {
        Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
        pose.translation() = Eigen::Vector3d(x, y, 0.0);
        return ScanVoxels(pose, Cloud(rng, 40.0f, 0.5), 0.5, 1);
    };
    const PackedVoxels here = scan_at(-3.0, 2.0);
    const VoxelColumns columns_here = ColumnsOf(here);
    EXPECT_TRUE(columns_here.bounded);
    EXPECT_EQ(columns_here.size, here.size);
    std::size_t sum = 0;
    for (const std::uint32_t cell : columns_here.cells) sum += cell & 0xFFFF;
    EXPECT_EQ(sum, here.size);
    EXPECT_EQ(CommonVoxelsAtMost(columns_here, columns_here), here.size);
    bool proved_far_apart = false;
    for (const double distance : {0.0, 5.0, 20.0, 45.0, 80.0, 200.0}) {
        const PackedVoxels there = scan_at(-3.0 + distance, 2.0 - distance / 3);
        const VoxelColumns columns_there = ColumnsOf(there);
        const std::size_t smaller = std::min(here.size, there.size);
        const double overlap = OverlapCoefficient(here, there);
        const std::size_t common = static_cast<std::size_t>(std::llround(overlap * static_cast<double>(smaller)));
        const std::size_t bound = CommonVoxelsAtMost(columns_here, columns_there);
        EXPECT_GE(bound, common) << distance << " m";
        EXPECT_EQ(bound, CommonVoxelsAtMost(columns_there, columns_here));
        if (static_cast<double>(bound) / static_cast<double>(smaller) <= 0.5) proved_far_apart = true;
        if (distance >= 200.0) EXPECT_EQ(bound, 0u);
    }
    EXPECT_TRUE(proved_far_apart);
    // Empty, and sets spanning more columns than the summary holds: no bound (the smaller size).
    EXPECT_EQ(ColumnsOf(PackedVoxels{}).cells.size(), 0u);
    PackedVoxels wide = scan_at(0.0, 0.0);
    MergeVoxels(wide, scan_at(5000.0, 0.0));
    const VoxelColumns columns_wide = ColumnsOf(wide);
    EXPECT_FALSE(columns_wide.bounded);
    EXPECT_EQ(CommonVoxelsAtMost(columns_wide, columns_here), std::min(wide.size, here.size));
}

TEST(PackedVoxels, MergingScanSetsInAnyOrderGivesTheAccumulatedSet) {
    // What the chain's pass relies on: each scan's set made on its own (any thread), merged later in
    // the run's order, is byte for byte the set AddVoxels accumulates scan after scan.
    std::mt19937 rng(11);
    std::vector<std::pair<Eigen::Isometry3d, std::vector<Eigen::Vector3f>>> scans;
    for (int scan = 0; scan < 4; ++scan) {
        Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
        pose.translation() = Eigen::Vector3d(scan * 2.3, scan * -0.7, 0.1 * scan);
        pose.linear() = Eigen::AngleAxisd(0.2 * scan, Eigen::Vector3d::UnitZ()).toRotationMatrix();
        scans.emplace_back(pose, Cloud(rng, 25.0f, 0.5));
    }
    for (const std::size_t subsample : {std::size_t{1}, std::size_t{4}}) {
        PackedVoxels accumulated, merged, reversed;
        std::vector<PackedVoxels> singles;
        for (const auto& [pose, points] : scans) {
            AddVoxels(accumulated, pose, points, 0.5, subsample);
            singles.push_back(ScanVoxels(pose, points, 0.5, subsample));
        }
        for (const auto& single : singles) MergeVoxels(merged, single);
        for (auto it = singles.rbegin(); it != singles.rend(); ++it) MergeVoxels(reversed, *it);
        EXPECT_EQ(merged.bytes, accumulated.bytes);
        EXPECT_EQ(merged.size, accumulated.size);
        EXPECT_EQ(reversed.bytes, accumulated.bytes);
        EXPECT_EQ(reversed.size, accumulated.size);
        // Each scan's set is part of the union, and the union is larger than any one.
        for (const auto& single : singles) {
            EXPECT_EQ(OverlapCoefficient(single, accumulated), 1.0);
            EXPECT_LT(single.size, accumulated.size);
        }
    }
    PackedVoxels empty;
    MergeVoxels(empty, PackedVoxels{});
    EXPECT_EQ(empty.size, 0u);
    EXPECT_TRUE(empty.bytes.empty());
}

}  // namespace
}  // namespace revisit
