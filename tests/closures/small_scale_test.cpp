#include <gtest/gtest.h>

#include <iostream>

#include "closures/detector.hpp"
#include "test_support.hpp"

namespace revisit {
namespace {

/// A handheld / Livox-like walk: two laps around a 16 m courtyard, sparse short-range points, local maps
/// of ~21 m of travel (three per lap). METHOD.md 5b: the published settings find almost nothing here.
struct Walk {
    std::vector<LocalMap> maps;
};

Walk MakeWalk(std::uint32_t seed) {
    const auto world = test::MakeBoxWorld(seed, 22.0, 40, 0.25, 3.0);
    // Square loop, corners at +-8 m, 0.5 m steps; the second lap 0.4 m further out.
    std::vector<Eigen::Isometry3d> route;
    for (int lap = 0; lap < 2; ++lap) {
        const double h = 8.0 + 0.4 * lap;
        const Eigen::Vector2d corners[4] = {{-h, -h}, {h, -h}, {h, h}, {-h, h}};
        for (int side = 0; side < 4; ++side) {
            const Eigen::Vector2d a = corners[side], b = corners[(side + 1) % 4];
            const int steps = int((b - a).norm() / 0.5);
            const double yaw = std::atan2((b - a).y(), (b - a).x());
            for (int i = 0; i < steps; ++i) {
                const Eigen::Vector2d p = a + (b - a) * (double(i) / steps);
                route.push_back(PoseFromXYZRPY(p.x(), p.y(), 1.2, 0.0, 0.0, yaw));
            }
        }
    }
    Walk walk;
    const int per_map = 42;  // 21 m of travel
    for (int m = 0; m * per_map < int(route.size()); ++m) {
        const auto first = route.begin() + m * per_map;
        const auto last = route.begin() + std::min<int>(int(route.size()), (m + 1) * per_map);
        std::vector<Eigen::Isometry3d> segment(first, last);
        // Sparse sensor: every 4th pose, 15 m range.
        std::vector<Eigen::Isometry3d> sparse;
        for (std::size_t i = 0; i < segment.size(); i += 4) sparse.push_back(segment[i]);
        auto map = test::SimulateLocalMap(world, sparse, m, seed * 100 + std::uint32_t(m), 15.0);
        map.first_scan = std::size_t(m * per_map);
        map.last_scan = std::size_t(m * per_map) + segment.size() - 1;
        map.travel_start = m * per_map * 0.5;
        map.travel_end = map.travel_start + 0.5 * double(segment.size() - 1);
        walk.maps.push_back(std::move(map));
    }
    return walk;
}

struct Score {
    int correct = 0;
    int wrong = 0;
};

Score Evaluate(const Walk& walk, const ClosureDetectorConfig& config) {
    Score score;
    for (const auto& c : DetectClosures(walk.maps, config)) {
        const auto& q = walk.maps[std::size_t(c.query_id)];
        const auto& r = walk.maps[std::size_t(c.ref_id)];
        const Eigen::Isometry3d truth = q.T_world_map.inverse() * r.T_world_map;
        const bool ok = test::TranslationError(c.T_query_ref, truth) < 1.0 && test::YawError(c.T_query_ref, truth) < 3.0 * M_PI / 180.0;
        (ok ? score.correct : score.wrong)++;
    }
    return score;
}

TEST(SmallScale, RobustSettingsFindRevisitsThePaperSettingsMiss) {
    auto paper = ClosureDetectorConfig::Paper();
    paper.min_matches = 10;  // the paper's small-FOV setting
    auto robust = ClosureDetectorConfig::Robust(/*skip_recent_travel_m=*/15.0);
    auto paper_skip = paper;  // ablation: only the skip-by-travel rule changed
    paper_skip.skip_recent_travel = 15.0;
    Score total_paper, total_robust, total_paper_skip;
    for (std::uint32_t seed : {1u, 2u, 3u, 4u}) {
        const auto walk = MakeWalk(seed);
        const auto p = Evaluate(walk, paper), r = Evaluate(walk, robust), ps = Evaluate(walk, paper_skip);
        std::cout << "walk " << seed << " (" << walk.maps.size() << " maps): paper " << p.correct << " correct / " << p.wrong
                  << " wrong, paper + skip by travel " << ps.correct << " / " << ps.wrong << ", robust " << r.correct
                  << " correct / " << r.wrong << " wrong\n";
        total_paper_skip.correct += ps.correct;
        total_paper.correct += p.correct, total_paper.wrong += p.wrong;
        total_robust.correct += r.correct, total_robust.wrong += r.wrong;
    }
    EXPECT_GT(total_robust.correct, total_paper.correct + 2);
    EXPECT_GT(total_robust.correct, total_paper_skip.correct);  // scaling and keypoint budget add to the skip rule
    EXPECT_LE(total_robust.wrong, total_robust.correct / 10);
}

}  // namespace
}  // namespace revisit
