#include <gtest/gtest.h>

#include <iostream>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include "closures/detector.hpp"
#include "test_support.hpp"

namespace revisit {
namespace {

TEST(ClosureDetectorSim, OppositeDirectionRevisitIsRecovered) {
    const auto world = test::MakeBoxWorld(21);
    // Forward pass heading east, later the same street heading west, 8 m further along.
    const auto forward = test::StraightRoute(-20.0, 0.0, 0.0);
    const auto backward = test::StraightRoute(28.0, 1.5, M_PI);
    const LocalMap ref = test::SimulateLocalMap(world, forward, 0, 1);
    const LocalMap query = test::SimulateLocalMap(world, backward, 1, 2);
    const Eigen::Isometry3d T_query_ref = query.T_world_map.inverse() * ref.T_world_map;
    auto config = ClosureDetectorConfig::Paper();
    config.skip_recent_maps = 0;
    ClosureDetector detector(config);
    detector.AddMap(ref);
    const auto closures = detector.AddMap(query);
    ASSERT_EQ(closures.size(), 1u);
    EXPECT_GE(closures[0].num_inliers, 10);
    EXPECT_LT(test::TranslationError(closures[0].T_query_ref, T_query_ref), 0.5);
    EXPECT_LT(test::YawError(closures[0].T_query_ref, T_query_ref), 1.0 * M_PI / 180.0);
}

TEST(ClosureDetectorSim, SameClosuresWithOneThreadOrMany) {
    const auto world = test::MakeBoxWorld(33);
    std::vector<LocalMap> maps;
    for (int i = 0; i < 6; ++i) {
        maps.push_back(test::SimulateLocalMap(world, test::StraightRoute(-60.0 + 25.0 * (i % 3), 2.0 * i, 0.1 * i), i, i));
    }
    auto config = ClosureDetectorConfig::Paper();
    config.skip_recent_maps = 1;
    const auto many = DetectClosures(maps, config);
    std::vector<Closure> one;
    {
        tbb::global_control single(tbb::global_control::max_allowed_parallelism, 1);
        one = DetectClosures(maps, config);
    }
    ASSERT_GE(many.size(), 3u);  // maps 3-5 revisit the places of maps 0-2
    ASSERT_EQ(one.size(), many.size());
    for (std::size_t i = 0; i < one.size(); ++i) {
        EXPECT_EQ(one[i].query_id, many[i].query_id);
        EXPECT_EQ(one[i].ref_id, many[i].ref_id);
        EXPECT_EQ(one[i].inlier_mask, many[i].inlier_mask);
        EXPECT_TRUE(one[i].T_query_ref.isApprox(many[i].T_query_ref, 1e-12));
    }
}

TEST(ClosureDetectorSim, NoClosureBetweenUnrelatedPlaces) {
    // 48 maps, each from its own random world: 1128 pairs, every pair with a match is verified.
    constexpr int kWorlds = 48;
    std::vector<LocalMap> maps(kWorlds);
    tbb::parallel_for(0, kWorlds, [&](int w) {
        const auto world = test::MakeBoxWorld(1000 + std::uint32_t(w), 90.0, 70);
        maps[w] = test::SimulateLocalMap(world, test::StraightRoute(-10.0, 0.0, 0.3 * w), w, std::uint32_t(w));
    });
    for (const auto& [name, base] : {std::pair{"paper", ClosureDetectorConfig::Paper()},
                                     std::pair{"later", ClosureDetectorConfig::Later()},
                                     std::pair{"robust", ClosureDetectorConfig::Robust(0.0)},
                                     std::pair{"default (rematch)", ClosureDetectorConfig{}}}) {
        auto config = base;
        config.skip_recent_maps = 0;
        config.selection = CandidateSelection::kAllAboveMin;
        config.min_matches = 2;  // verify every pair that has two matches, not only the top voted
        ClosureDetector detector(config);
        int accepted = 0, verified = 0, max_inliers = 0;
        for (const auto& map : maps) {
            for (const auto& c : detector.AddMap(map)) {
                max_inliers = std::max(max_inliers, c.num_inliers);
                ++accepted;
            }
            verified += detector.last_stats().num_candidates;
        }
        const int pairs = kWorlds * (kWorlds - 1) / 2;
        std::cout << name << ": " << accepted << " of " << pairs << " pairs accepted, " << verified
                  << " verified, largest accepted inliers " << max_inliers << "\n";
        EXPECT_LE(accepted, pairs / 100) << name;
    }
}

TEST(ClosureDetectorSim, AShortDrivesTopHalfKeepsAtLeastMinCandidates) {
    // Eight maps of one street world: the ninth's top half is 4 maps, the floor keeps every map with
    // enough matches (a short drive's revisit can rank just below half of a handful of maps).
    const auto world = test::MakeBoxWorld(47);
    std::vector<LocalMap> maps;
    for (int i = 0; i < 9; ++i) maps.push_back(test::SimulateLocalMap(world, test::StraightRoute(-60.0 + 12.0 * i, 1.0 * (i % 3), 0.05 * i), i, i));
    const auto compared = [&](int min_candidates) {
        ClosureDetectorConfig config;
        config.skip_recent_maps = 0;
        config.min_matches = 1;
        config.min_candidates = min_candidates;
        ClosureDetector detector(config);
        for (const auto& map : maps) detector.AddMap(map);  // the last AddMap is the ninth map's
        int count = 0, eligible = 0;
        for (const auto& c : detector.last_comparisons()) {
            count += c.stage == ComparisonStage::kCompared;
            eligible += c.stage == ComparisonStage::kCompared || c.stage == ComparisonStage::kNotSelected;
        }
        return std::pair{count, eligible};
    };
    const auto [paper, eligible] = compared(1);
    ASSERT_GE(eligible, 6);  // the street's maps share enough to vote for most of them
    EXPECT_EQ(paper, 4);     // half of the 8 maps in the database
    EXPECT_EQ(compared(10).first, eligible);
    EXPECT_EQ(compared(6).first, 6);
}

}  // namespace
}  // namespace revisit
