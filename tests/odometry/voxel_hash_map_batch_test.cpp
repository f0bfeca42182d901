// The odometry map's parallel batch update (issue 19) gives exactly the serial result at any thread
// count, and its neighbourhood cache the lookup's answers.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "odometry/shard_groups.hpp"
#include "odometry/preprocess.hpp"
#include "odometry/voxel_hash_map.hpp"

namespace revisit {
namespace {

/// A scan-like cloud: 120,000 points out to 110 m, denser near the sensor, with a few non-finite ones.
std::vector<Eigen::Vector3f> ScanLike(unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> angle(-3.14159f, 3.14159f), height(-2.0f, 4.0f), unit(0.0f, 1.0f);
    std::vector<Eigen::Vector3f> points;
    for (int i = 0; i < 120000; ++i) {
        const float range = 110.0f * unit(rng) * unit(rng), a = angle(rng);
        points.emplace_back(range * std::cos(a), range * std::sin(a), height(rng));
    }
    points[17].x() = std::numeric_limits<float>::quiet_NaN();
    points[99].y() = std::numeric_limits<float>::infinity();
    return points;
}

template <typename F>
auto WithThreads(int threads, F&& f) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, std::size_t(threads));
    return f();
}

TEST(VoxelHashMap, AddingABatchEqualsAddingPointByPointAtAnyThreadCount) {
    const auto scan = ScanLike(5);
    std::vector<Eigen::Vector3d> first, second;
    for (std::size_t i = 0; i < scan.size(); ++i) {
        if (!scan[i].allFinite()) continue;
        (i % 2 ? first : second).push_back(scan[i].cast<double>());
    }
    // One by one: every batch of one point takes the serial path.
    VoxelHashMap reference(1.0, 20);
    for (const auto* batch : {&first, &second}) {
        for (const auto& p : *batch) reference.AddPoints({p});
        reference.RemoveFarFrom(batch->front(), 60.0);
    }
    for (const int threads : {1, 2, 4}) {
        WithThreads(threads, [&] {
            VoxelHashMap map(1.0, 20);
            for (const auto* batch : {&first, &second}) {
                map.AddPoints(*batch);  // the second batch falls mostly into voxels of the first
                map.RemoveFarFrom(batch->front(), 60.0);
            }
            EXPECT_EQ(map.NumVoxels(), reference.NumVoxels()) << threads << " threads";
            EXPECT_EQ(map.Points(), reference.Points()) << threads << " threads";  // same slots, same order
            return 0;
        });
    }
}

TEST(VoxelHashMap, NeighbourhoodCacheReusesTheNearestPointOnlyWhenItCannotHaveChanged) {
    // Map points on a 0.25 m lattice (many exact ties between neighbours) and queries creeping by
    // 0-3 mm per step, as in ICP's late iterations: most answers come from the cache, and each
    // must be the very point (first of equals included) that a full search returns.
    std::vector<Eigen::Vector3d> lattice;
    for (int x = -20; x < 20; ++x)
        for (int y = -20; y < 20; ++y)
            for (int z = -4; z < 4; ++z) lattice.emplace_back(0.25 * x, 0.25 * y, 0.25 * z);
    VoxelHashMap map(1.0, 20);
    map.AddPoints(lattice);
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> position(-4.0, 4.0), height(-0.9, 0.9), step(-0.0017, 0.0017);
    std::vector<Eigen::Vector3d> queries;
    for (int i = 0; i < 2000; ++i) queries.emplace_back(position(rng), position(rng), height(rng));
    for (int i = 0; i < 200; ++i) queries.emplace_back(0.125 + 0.25 * (i % 8), 0.0, 0.0);  // midway between two
    std::vector<VoxelHashMap::Neighbourhood> caches(queries.size());
    for (int iteration = 0; iteration < 20; ++iteration) {
        for (std::size_t i = 0; i < queries.size(); ++i) {
            if (i < 2000) queries[i] += Eigen::Vector3d(step(rng), step(rng), step(rng));
            const Eigen::Vector3d* expected = map.FindNearest(queries[i], 0.3);
            ASSERT_EQ(map.FindNearest(queries[i], 0.3, caches[i]), expected) << "query " << i << " iteration " << iteration;
        }
    }
}

TEST(VoxelHashMap, NeighbourhoodCacheKeepsNoAnswerOnlyWhileNothingCanComeInReach) {
    // Sparse map points (0.7 m apart) and a 0.3 m reach: most queries find nothing, and those creeping
    // by up to 2 cm per step towards the points come into reach at some step: each answer, none or a
    // point, must be the full search's.
    std::vector<Eigen::Vector3d> sparse;
    for (int x = -8; x < 8; ++x)
        for (int y = -8; y < 8; ++y) sparse.emplace_back(0.7 * x, 0.7 * y, 0.0);
    VoxelHashMap map(1.0, 20);
    map.AddPoints(sparse);
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> position(-5.0, 5.0), height(0.2, 0.6);
    std::vector<Eigen::Vector3d> queries;
    for (int i = 0; i < 2000; ++i) queries.emplace_back(position(rng), position(rng), height(rng));
    std::vector<VoxelHashMap::Neighbourhood> caches(queries.size());
    std::size_t none = 0, found = 0;
    for (int iteration = 0; iteration < 20; ++iteration) {
        for (std::size_t i = 0; i < queries.size(); ++i) {
            queries[i].z() -= 0.02;
            const Eigen::Vector3d* expected = map.FindNearest(queries[i], 0.3);
            ASSERT_EQ(map.FindNearest(queries[i], 0.3, caches[i]), expected) << "query " << i << " iteration " << iteration;
            (expected == nullptr ? none : found) += 1;
        }
    }
    EXPECT_GT(none, 10000u);
    EXPECT_GT(found, 1000u);
}

TEST(VoxelHashMap, NeighbourhoodCacheGivesTheSameNearestPointAsTheLookup) {
    const auto scan = ScanLike(9);
    std::vector<Eigen::Vector3d> points;
    for (const auto& p : scan)
        if (p.allFinite()) points.push_back(p.cast<double>());
    VoxelHashMap map(1.0, 20);
    map.AddPoints(points);
    // Queries drifting by a few cm per "iteration", as source points do during ICP: most stay in
    // their voxel (the cache answers), some cross into the next one (the cache refills).
    std::vector<Eigen::Vector3d> queries(points.begin(), points.begin() + 3000);
    std::vector<VoxelHashMap::Neighbourhood> caches(queries.size());
    std::size_t found = 0;
    for (int iteration = 0; iteration < 6; ++iteration) {
        for (std::size_t i = 0; i < queries.size(); ++i) {
            queries[i] += Eigen::Vector3d(0.07, -0.05, 0.02);
            const Eigen::Vector3d* expected = map.FindNearest(queries[i], 2.0);
            ASSERT_EQ(map.FindNearest(queries[i], 2.0, caches[i]), expected) << "query " << i;
            found += expected != nullptr;
        }
    }
    EXPECT_GT(found, 6 * 2900u);
}

}  // namespace
}  // namespace revisit
