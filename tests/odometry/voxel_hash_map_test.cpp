#include <gtest/gtest.h>

#include <random>

#include "odometry/adaptive_threshold.hpp"
#include "odometry/preprocess.hpp"
#include "odometry/voxel_hash_map.hpp"
#include "core/se3.hpp"

namespace revisit {
namespace {

std::vector<Eigen::Vector3d> RandomPoints(int n, double extent, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(-extent, extent);
    std::vector<Eigen::Vector3d> points(n);
    for (auto& p : points) p = Eigen::Vector3d(u(rng), u(rng), u(rng));
    return points;
}

TEST(VoxelHashMap, PrunedSearchFindsTheExactNearestPointOfThe27Voxels) {
    VoxelHashMap map(1.0, 20);
    map.AddPoints(RandomPoints(20000, 6.0, 1));
    const std::vector<Eigen::Vector3d> stored = map.Points();
    for (const auto& query : RandomPoints(2000, 5.0, 2)) {
        // Brute force over the stored points of the 27 voxels around the query.
        const Voxel centre = VoxelOf(query, 1.0);
        double best = 0.8 * 0.8;
        const Eigen::Vector3d* expected = nullptr;
        for (const auto& p : stored) {
            if ((VoxelOf(p, 1.0) - centre).cwiseAbs().maxCoeff() > 1) continue;
            if ((p - query).squaredNorm() < best) {
                best = (p - query).squaredNorm();
                expected = &p;
            }
        }
        const Eigen::Vector3d* found = map.FindNearest(query, 0.8);
        ASSERT_EQ(found == nullptr, expected == nullptr);
        if (found) {
            EXPECT_EQ(*found, *expected);
        }
    }
}

TEST(VoxelHashMap, VoxelsKeepAtMostNPointsSpacedBySizeOverSqrtN) {
    VoxelHashMap map(1.0, 20);
    std::vector<Eigen::Vector3d> points = RandomPoints(5000, 0.5, 3);
    for (auto& p : points) p += Eigen::Vector3d::Constant(0.5);  // all inside voxel (0, 0, 0)
    map.AddPoints(points);
    EXPECT_EQ(map.NumVoxels(), 1u);
    const auto stored = map.Points();
    EXPECT_EQ(stored.size(), 20u);
    for (std::size_t i = 0; i < stored.size(); ++i) {
        for (std::size_t j = i + 1; j < stored.size(); ++j) EXPECT_GE((stored[i] - stored[j]).norm(), 1.0 / std::sqrt(20.0));
    }
}

TEST(VoxelHashMap, RemovesVoxelsFartherThanTheRadiusAndStaysSearchable) {
    VoxelHashMap map(1.0, 5);
    const auto points = RandomPoints(20000, 50.0, 4);
    map.AddPoints(points);
    map.RemoveFarFrom(Eigen::Vector3d(10.0, 0.0, 0.0), 20.0);
    const auto kept = map.Points();
    ASSERT_FALSE(kept.empty());
    // Voxels are judged by their first point: every kept point is within radius + voxel diagonal.
    for (const auto& p : kept) EXPECT_LT((p - Eigen::Vector3d(10.0, 0.0, 0.0)).norm(), 20.0 + std::sqrt(3.0));
    // After the swap-removals every kept point is still found at distance zero.
    for (std::size_t i = 0; i < kept.size(); i += 7) {
        const Eigen::Vector3d* found = map.FindNearest(kept[i], 0.1);
        ASSERT_NE(found, nullptr);
        EXPECT_EQ(*found, kept[i]);
    }
}

TEST(VoxelHashMap, DropsVoxelsNoPointFellInSinceTheOldestKeptStamp) {
    VoxelHashMap map(1.0, 1);  // one point per voxel: a voxel is full after its first point
    map.SetStamp(0.0);
    map.AddPoints({Eigen::Vector3d(0.5, 0.5, 0.5), Eigen::Vector3d(5.5, 0.5, 0.5)});
    map.SetStamp(10.0);
    // Seen again (full, so nothing is added) and a new voxel.
    map.AddPoints({Eigen::Vector3d(0.6, 0.6, 0.6), Eigen::Vector3d(9.5, 0.5, 0.5)});
    map.RemoveFarFrom(Eigen::Vector3d::Zero(), 100.0, 5.0);
    EXPECT_EQ(map.NumVoxels(), 2u);
    EXPECT_NE(map.FindNearest(Eigen::Vector3d(0.5, 0.5, 0.5), 0.1), nullptr);
    EXPECT_NE(map.FindNearest(Eigen::Vector3d(9.5, 0.5, 0.5), 0.1), nullptr);
    EXPECT_EQ(map.FindNearest(Eigen::Vector3d(5.5, 0.5, 0.5), 0.1), nullptr);
}

TEST(VoxelDownsample, KeepsTheFirstPointOfEachVoxel) {
    const std::vector<Eigen::Vector3d> points = {{0.1, 0.1, 0.1}, {0.2, 0.2, 0.2}, {1.5, 0.1, 0.1}, {-0.1, 0.1, 0.1}};
    const auto kept = VoxelDownsample(points, 1.0);
    ASSERT_EQ(kept.size(), 3u);
    EXPECT_EQ(kept[0], points[0]);
    EXPECT_EQ(kept[1], points[2]);
    EXPECT_EQ(kept[2], points[3]);
}

TEST(AdaptiveThreshold, StartsAtTheInitialValueAndIgnoresStandingStill) {
    AdaptiveThreshold threshold(2.0, 0.1, 100.0);
    EXPECT_EQ(threshold.Sigma(), 2.0);
    threshold.Update(Eigen::Isometry3d::Identity());
    threshold.Update(PoseFromXYZRPY(0.05, 0.0, 0.0, 0.0, 0.0, 0.0));
    EXPECT_EQ(threshold.Sigma(), 2.0);
    EXPECT_EQ(threshold.NumSamples(), 0u);
    // Model errors 0.3 m and |t| + 2 r sin(theta / 2) = 0.4 + 200 sin(0.0005) m: sigma is their RMS.
    threshold.Update(PoseFromXYZRPY(0.3, 0.0, 0.0, 0.0, 0.0, 0.0));
    threshold.Update(PoseFromXYZRPY(0.0, 0.4, 0.0, 0.0, 0.0, 0.001));
    const double e2 = 0.4 + 200.0 * std::sin(0.0005);
    EXPECT_NEAR(threshold.Sigma(), std::sqrt((0.3 * 0.3 + e2 * e2) / 2.0), 1e-9);
}

}  // namespace
}  // namespace revisit
