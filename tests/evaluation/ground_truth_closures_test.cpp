#include "evaluation/ground_truth_closures.hpp"

#include "core/error.hpp"
#include "core/se3.hpp"
#include "evaluation/synthetic_route.hpp"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <numeric>
#include <sstream>

namespace revisit {
namespace {

Eigen::Vector3f VoxelCentre(int i, int j, int k) { return Eigen::Vector3f(0.5f * i + 0.25f, 0.5f * j + 0.25f, 0.5f * k + 0.25f); }

/// Three scans, one per 2 m segment: at x = 0, x = 3 and back at x = 0 (travel 0, 3, 6 m).
struct HandFixture {
    Poses poses = {PoseFromXYZRPY(0, 0, 0, 0, 0, 0), PoseFromXYZRPY(3, 0, 0, 0, 0, 0), PoseFromXYZRPY(0, 0, 0, 0, 0, 0)};
    ScanPointsFn points = [](std::size_t scan) -> std::vector<Eigen::Vector3f> {
        const Eigen::Vector3f scan1_origin(3.0f, 0.0f, 0.0f);
        switch (scan) {
            case 0: return {VoxelCentre(0, 0, 0), VoxelCentre(1, 0, 0), VoxelCentre(2, 0, 0), VoxelCentre(3, 0, 0)};
            case 1: return {VoxelCentre(0, 0, 0) - scan1_origin, VoxelCentre(0, 5, 0) - scan1_origin,
                            VoxelCentre(0, 6, 0) - scan1_origin, VoxelCentre(0, 7, 0) - scan1_origin};
            default:  // two voxels of scan 0 (one hit twice) and one new: overlap 2 / min(4, 3)
                return {VoxelCentre(0, 0, 0), Eigen::Vector3f(0.3f, 0.3f, 0.3f), VoxelCentre(1, 0, 0), VoxelCentre(9, 9, 9)};
        }
    };
    GtClosureConfig config() const {
        GtClosureConfig c;
        c.max_range = 10.0;
        c.travel_gap_ranges = 0.1;  // 1 m: every later segment qualifies
        return c;
    }
};

TEST(ComputeGroundTruthClosures, HandComputedOverlaps) {
    const HandFixture fixture;
    const auto closures = ComputeGroundTruthClosures(fixture.poses, fixture.points, fixture.config());
    ASSERT_EQ(closures.segments.size(), 3u);
    EXPECT_EQ(closures.num_candidate_pairs, 3u);
    ASSERT_EQ(closures.segment_pairs.size(), 1u);  // 0-1: 1/4, 1-2: 1/3, 0-2: 2/3
    EXPECT_EQ(closures.segment_pairs[0].earlier, 0u);
    EXPECT_EQ(closures.segment_pairs[0].later, 2u);
    EXPECT_NEAR(closures.segment_pairs[0].overlap, 2.0 / 3.0, 1e-12);
    EXPECT_EQ(closures.scan_pairs, (std::vector<ScanPair>{{0, 2}}));
    // By distance in 2 m bins: 0-2 at 0 m closes, 0-1 and 1-2 at 3 m do not.
    EXPECT_EQ(closures.distance_bin, 2.0);
    EXPECT_EQ(closures.candidates_by_distance, (std::vector<std::size_t>{1, 2}));
    EXPECT_EQ(closures.closing_by_distance, (std::vector<std::size_t>{1, 0}));
    EXPECT_EQ(OverlapDistance(closures), 2.0);

    auto config = fixture.config();
    config.min_overlap = 0.7;  // above 2/3: nothing closes
    EXPECT_TRUE(ComputeGroundTruthClosures(fixture.poses, fixture.points, config).scan_pairs.empty());
    config = fixture.config();
    config.travel_gap_ranges = 0.4;  // 4 m: only the 0-2 pair is far enough along the path
    EXPECT_EQ(ComputeGroundTruthClosures(fixture.poses, fixture.points, config).num_candidate_pairs, 1u);
    config = fixture.config();
    config.max_range = 2.0;  // the pairs 0-1 and 1-2 start 3 m apart
    EXPECT_EQ(ComputeGroundTruthClosures(fixture.poses, fixture.points, config).num_candidate_pairs, 1u);
}

TEST(OverlapDistance, TheDistanceRuleThatBestReproducesTheOverlapRule) {
    GtClosures closures;
    closures.distance_bin = 2.0;
    closures.candidates_by_distance = {10, 10, 10, 10};
    closures.closing_by_distance = {10, 8, 2, 3};
    EXPECT_EQ(OverlapDistance(closures), 4.0);  // right minus wrong below: 10, 16, 10, 6
    closures.closing_by_distance = {10, 8, 2, 9};
    EXPECT_EQ(OverlapDistance(closures), 8.0);  // 10, 16, 10, 18: a far bin counts only when it outweighs the gap
    closures.closing_by_distance = {10, 5, 5, 0};
    EXPECT_EQ(OverlapDistance(closures), 2.0);  // ties keep the nearest
    closures.closing_by_distance = {4, 5, 0, 0};
    EXPECT_EQ(OverlapDistance(closures), 0.0);  // no distance at which most pairs overlap
    EXPECT_EQ(OverlapDistance(GtClosures{}), 0.0);
}

TEST(CutSegments, TwoMetresOfTravelEach) {
    Poses poses;
    for (int i = 0; i < 10; ++i) poses.push_back(PoseFromXYZRPY(0.7 * i, 0, 0, 0, 0, 0));
    const auto segments = CutSegments(poses, 2.0);
    // travel 0, .7, 1.4 | 2.1, 2.8, 3.5 | 4.2, 4.9, 5.6 | 6.3
    ASSERT_EQ(segments.size(), 4u);
    EXPECT_EQ(segments[1].first_scan, 3u);
    EXPECT_EQ(segments[1].last_scan, 5u);
    EXPECT_EQ(segments[3].first_scan, 9u);
    EXPECT_EQ(segments[3].last_scan, 9u);
}

class SquareLoop : public ::testing::Test {
  protected:
    static constexpr double kSensorRange = 10.0;  // what a scan sees
    static constexpr double kMaxRange = 20.0;     // the config's range: candidates, travel gap 40 m
    Poses poses = testing::SquareLoopRoute(200);  // 1.25 laps: scans 160-199 revisit scans 0-39
    std::vector<Eigen::Vector3d> walls = testing::CorridorWalls();
    ScanPointsFn points = [this](std::size_t scan) { return testing::VisiblePoints(walls, poses[scan], kSensorRange); };
    GtClosureConfig config() const {
        GtClosureConfig c;
        c.max_range = kMaxRange;
        return c;
    }
};

TEST_F(SquareLoop, FindsTheRevisitAndOnlyPlausiblePairs) {
    const auto closures = ComputeGroundTruthClosures(poses, points, config());
    const auto& pairs = closures.scan_pairs;
    ASSERT_FALSE(pairs.empty());
    EXPECT_TRUE(std::is_sorted(pairs.begin(), pairs.end()));
    // Every scan of the second lap closes with the scan at the same place in the first.
    for (std::size_t s = 160; s < 200; ++s)
        EXPECT_TRUE(std::binary_search(pairs.begin(), pairs.end(), ScanPair{s - 160, s})) << s;
    for (const auto& pair : pairs) {
        EXPECT_GE(pair.second - pair.first, 40u) << pair.first << "," << pair.second;  // 1 m per scan
        // Scans farther apart than twice the sensor range (plus a segment each) share no point.
        const double distance = (poses[pair.first].translation() - poses[pair.second].translation()).norm();
        EXPECT_LT(distance, 2.0 * kSensorRange + 4.0) << pair.first << "," << pair.second;
        // Scans 60-100 ((40,20) .. (20,40)) pass nowhere else within 20 m.
        EXPECT_FALSE(pair.first >= 60 && pair.first <= 100) << pair.first << "," << pair.second;
        EXPECT_FALSE(pair.second >= 60 && pair.second <= 100) << pair.first << "," << pair.second;
    }
    // The candidates by distance account for every pair; the revisit's pairs close near each other
    // and stop closing before the sensor's views part (two ranges apart).
    std::size_t candidates = 0, closing = 0, closing_below = 0, candidates_below = 0;
    const double overlap_distance = OverlapDistance(closures);
    for (std::size_t b = 0; b < closures.candidates_by_distance.size(); ++b) {
        candidates += closures.candidates_by_distance[b];
        closing += closures.closing_by_distance[b];
        if ((b + 1) * closures.distance_bin > overlap_distance) continue;
        candidates_below += closures.candidates_by_distance[b];
        closing_below += closures.closing_by_distance[b];
    }
    EXPECT_EQ(candidates, closures.num_candidate_pairs);
    EXPECT_EQ(closing, closures.segment_pairs.size());
    EXPECT_GT(overlap_distance, 2.0);
    EXPECT_LT(overlap_distance, 2.0 * kSensorRange);
    EXPECT_GT(2 * closing_below, candidates_below);
    for (const auto& segment_pair : closures.segment_pairs) {
        EXPECT_GT(segment_pair.overlap, 0.5);
        const auto& a = closures.segments[segment_pair.earlier];
        const auto& b = closures.segments[segment_pair.later];
        const double distance = (poses[a.first_scan].translation() - poses[b.first_scan].translation()).norm();
        if (distance < 1e-6) {
            EXPECT_GT(segment_pair.overlap, 0.95);  // the same place seen again
        }
    }
}

TEST_F(SquareLoop, SameResultWithOneThread) {
    const auto parallel = ComputeGroundTruthClosures(poses, points, config());
    tbb::global_control one_thread(tbb::global_control::max_allowed_parallelism, 1);
    const auto serial = ComputeGroundTruthClosures(poses, points, config());
    EXPECT_EQ(serial.scan_pairs, parallel.scan_pairs);
    ASSERT_EQ(serial.segment_pairs.size(), parallel.segment_pairs.size());
    for (std::size_t k = 0; k < serial.segment_pairs.size(); ++k)
        EXPECT_EQ(serial.segment_pairs[k].overlap, parallel.segment_pairs[k].overlap);
}

TEST_F(SquareLoop, StreamingBuilderMatchesBatchAndSkipsUnneededScans) {
    const auto batch = ComputeGroundTruthClosures(poses, points, config());
    GroundTruthBuilder builder(poses, config());
    EXPECT_TRUE(builder.NeedsScan(5));
    EXPECT_FALSE(builder.NeedsScan(80));  // (40, 40): no place 40 m of travel away lies within 20 m
    std::size_t skipped = 0;
    for (std::size_t scan = 0; scan < poses.size(); ++scan) {
        if (!builder.NeedsScan(scan)) {
            ++skipped;
            continue;
        }
        builder.AddScan(scan, points(scan));
    }
    EXPECT_GT(skipped, 20u);
    const auto streamed = builder.Finish();
    EXPECT_EQ(streamed.scan_pairs, batch.scan_pairs);
    EXPECT_EQ(streamed.num_candidate_pairs, batch.num_candidate_pairs);
    ASSERT_EQ(streamed.segment_pairs.size(), batch.segment_pairs.size());
    for (std::size_t k = 0; k < batch.segment_pairs.size(); ++k)
        EXPECT_EQ(streamed.segment_pairs[k].overlap, batch.segment_pairs[k].overlap);
}

TEST_F(SquareLoop, SettlingAsTheScansArriveGivesTheSameClosuresAndFreesTheSetsOnTheWay) {
    const auto batch = ComputeGroundTruthClosures(poses, points, config());
    GroundTruthBuilder kept(poses, config()), settled(poses, config());
    std::size_t peak = 0;
    for (std::size_t scan = 0; scan < poses.size(); ++scan) {
        if (kept.NeedsScan(scan)) {
            kept.AddScan(scan, points(scan));
            settled.AddScan(scan, points(scan));
        }
        settled.Settle(scan + 1);
        peak = std::max(peak, settled.HeldBytes());
    }
    // Scans 0-39 wait for the second lap; the first lap's other sets go as soon as their last pair is done.
    EXPECT_GT(kept.HeldBytes(), 0u);
    EXPECT_LT(peak, kept.HeldBytes());
    EXPECT_EQ(settled.HeldBytes(), 0u);
    for (GroundTruthBuilder* builder : {&kept, &settled}) {
        const auto closures = builder->Finish();
        EXPECT_EQ(closures.scan_pairs, batch.scan_pairs);
        ASSERT_EQ(closures.segment_pairs.size(), batch.segment_pairs.size());
        for (std::size_t k = 0; k < batch.segment_pairs.size(); ++k)
            EXPECT_EQ(closures.segment_pairs[k].overlap, batch.segment_pairs[k].overlap);
    }
}

TEST_F(SquareLoop, StoredSetsWithinABudgetGiveTheSameClosuresAndAreLoadedAgainWhenDropped) {
    const auto batch = ComputeGroundTruthClosures(poses, points, config());
    // Each segment's set as SegmentVoxelFile stores it.
    const auto segments = CutSegments(poses, config().segment_length);
    std::vector<PackedVoxels> stored(segments.size());
    std::size_t all_bytes = 0;
    for (std::size_t s = 0; s < segments.size(); ++s) {
        for (std::size_t scan = segments[s].first_scan; scan <= segments[s].last_scan; ++scan)
            AddVoxels(stored[s], poses[scan], points(scan), config().voxel_size, config().voxel_subsample);
        all_bytes += stored[s].bytes.size();
    }
    const auto build = [&](std::size_t budget, std::vector<std::size_t>& loads, std::size_t& peak) {
        GroundTruthBuilder builder(poses, config());
        loads.assign(segments.size(), 0);
        builder.LoadSetsFrom(
            [&](std::size_t s) {
                ++loads[s];
                peak = std::max(peak, builder.HeldBytes());
                return stored[s];
            },
            budget);
        return builder.Finish();
    };
    std::vector<std::size_t> ample_loads, tight_loads;
    std::size_t ample_peak = 0, tight_peak = 0;
    const auto ample = build(all_bytes, ample_loads, ample_peak);
    const auto tight = build(3 * all_bytes / segments.size(), tight_loads, tight_peak);
    for (const GtClosures* closures : {&ample, &tight}) {
        EXPECT_EQ(closures->scan_pairs, batch.scan_pairs);
        EXPECT_EQ(closures->num_candidate_pairs, batch.num_candidate_pairs);
        ASSERT_EQ(closures->segment_pairs.size(), batch.segment_pairs.size());
        for (std::size_t k = 0; k < batch.segment_pairs.size(); ++k)
            EXPECT_EQ(closures->segment_pairs[k].overlap, batch.segment_pairs[k].overlap);
    }
    // With room for every set each is read once, and only the sets some pair needs.
    EXPECT_EQ(*std::max_element(ample_loads.begin(), ample_loads.end()), 1u);
    EXPECT_LT(std::accumulate(ample_loads.begin(), ample_loads.end(), std::size_t{0}), segments.size());
    // With room for a few, the first lap's sets are dropped while they wait and read again for the revisit,
    // and far fewer bytes are held.
    EXPECT_GT(std::accumulate(tight_loads.begin(), tight_loads.end(), std::size_t{0}),
              std::accumulate(ample_loads.begin(), ample_loads.end(), std::size_t{0}));
    EXPECT_LT(tight_peak, ample_peak / 2);
}

TEST_F(SquareLoop, ColumnBoundsSettleMostPairsWithoutTheirSetsAndGiveTheSameClosures) {
    const auto batch = ComputeGroundTruthClosures(poses, points, config());
    const auto segments = CutSegments(poses, config().segment_length);
    std::vector<PackedVoxels> stored(segments.size());
    for (std::size_t s = 0; s < segments.size(); ++s)
        for (std::size_t scan = segments[s].first_scan; scan <= segments[s].last_scan; ++scan)
            AddVoxels(stored[s], poses[scan], points(scan), config().voxel_size, config().voxel_subsample);
    const auto build = [&](bool bounded, std::size_t& loads, std::size_t& column_loads) {
        GroundTruthBuilder builder(poses, config());
        builder.LoadSetsFrom([&](std::size_t s) { return ++loads, stored[s]; }, std::size_t{1} << 30);
        if (bounded) builder.BoundOverlapsWith([&](std::size_t s) { return ++column_loads, ColumnsOf(stored[s]); });
        return builder.Finish();
    };
    std::size_t plain_loads = 0, bounded_loads = 0, column_loads = 0, unused = 0;
    const auto plain = build(false, plain_loads, unused);
    const auto bounded = build(true, bounded_loads, column_loads);
    EXPECT_EQ(bounded.scan_pairs, batch.scan_pairs);
    EXPECT_EQ(bounded.num_candidate_pairs, batch.num_candidate_pairs);
    EXPECT_EQ(bounded.candidates_by_distance, plain.candidates_by_distance);
    EXPECT_EQ(bounded.closing_by_distance, plain.closing_by_distance);
    ASSERT_EQ(bounded.segment_pairs.size(), batch.segment_pairs.size());
    ASSERT_GT(batch.segment_pairs.size(), 0u);
    for (std::size_t k = 0; k < batch.segment_pairs.size(); ++k)
        EXPECT_EQ(bounded.segment_pairs[k].overlap, batch.segment_pairs[k].overlap);
    // Fewer sets read: the pairs of views far apart along the square are settled by their columns.
    EXPECT_LT(bounded_loads, plain_loads);
    EXPECT_LE(column_loads, segments.size());  // each asked for once
}

TEST_F(SquareLoop, VoxelSubsamplingApproximatesTheOverlap) {
    const auto exact = ComputeGroundTruthClosures(poses, points, config());
    auto sampled_config = config();
    sampled_config.voxel_subsample = 4;
    const auto sampled = ComputeGroundTruthClosures(poses, points, sampled_config);
    std::size_t common = 0;
    for (const auto& s : sampled.segment_pairs) {
        for (const auto& e : exact.segment_pairs) {
            if (e.earlier != s.earlier || e.later != s.later) continue;
            ++common;
            EXPECT_NEAR(s.overlap, e.overlap, 0.1);
        }
    }
    EXPECT_GT(common, exact.segment_pairs.size() * 8 / 10);
}

TEST_F(SquareLoop, CacheRoundTripAndKeys) {
    const auto closures = ComputeGroundTruthClosures(poses, points, config());
    const std::string key = GroundTruthCacheKey(poses, config(), "square.bin 200");
    std::stringstream cache;
    WriteGroundTruthClosures(cache, closures, key);
    const std::string text = cache.str();

    std::istringstream in(text);
    const auto read = ReadGroundTruthClosures(in, key);
    ASSERT_TRUE(read.has_value());
    EXPECT_EQ(read->scan_pairs, closures.scan_pairs);
    ASSERT_EQ(read->segment_pairs.size(), closures.segment_pairs.size());
    EXPECT_EQ(read->segment_pairs.back().overlap, closures.segment_pairs.back().overlap);  // exact text
    EXPECT_EQ(read->segments.size(), closures.segments.size());
    EXPECT_EQ(read->num_candidate_pairs, closures.num_candidate_pairs);
    EXPECT_EQ(read->distance_bin, closures.distance_bin);
    EXPECT_EQ(read->candidates_by_distance, closures.candidates_by_distance);
    EXPECT_EQ(read->closing_by_distance, closures.closing_by_distance);

    std::istringstream other_key(text);
    EXPECT_FALSE(ReadGroundTruthClosures(other_key, "0000000000000000").has_value());
    std::istringstream truncated(text.substr(0, text.size() / 2));
    EXPECT_FALSE(ReadGroundTruthClosures(truncated, key).has_value());

    // Any change to a pose, the config or the salt changes the key.
    Poses moved = poses;
    moved[100].translation().x() += 1e-9;
    EXPECT_NE(GroundTruthCacheKey(moved, config(), "square.bin 200"), key);
    auto other = config();
    other.min_overlap = 0.6;
    EXPECT_NE(GroundTruthCacheKey(poses, other, "square.bin 200"), key);
    EXPECT_NE(GroundTruthCacheKey(poses, config(), "square.bin 201"), key);
    EXPECT_EQ(GroundTruthCacheKey(poses, config(), "square.bin 200"), key);
}

TEST(ComputeGroundTruthClosures, RejectsBadConfig) {
    const HandFixture fixture;
    auto config = fixture.config();
    config.voxel_size = 0.0;
    EXPECT_THROW(ComputeGroundTruthClosures(fixture.poses, fixture.points, config), ConfigError);
}

}  // namespace
}  // namespace revisit
