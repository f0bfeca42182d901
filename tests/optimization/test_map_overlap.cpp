#include <gtest/gtest.h>

#include <cmath>

#include "core/se3.hpp"
#include "optimization/map_overlap.hpp"

namespace revisit {
namespace {

/// The walls of a 12 m x 8 m room with a pillar, sampled every 5 cm: what a 2D laser's local map holds.
std::vector<Eigen::Vector3f> Room() {
    std::vector<Eigen::Vector3f> points;
    auto wall = [&](Eigen::Vector2f a, Eigen::Vector2f b) {
        const int n = int((b - a).norm() / 0.05f);
        for (int k = 0; k <= n; ++k) {
            const Eigen::Vector2f p = a + (b - a) * (float(k) / float(n));
            points.emplace_back(p.x(), p.y(), 0.0f);
        }
    };
    wall({0, 0}, {12, 0}), wall({12, 0}, {12, 8}), wall({12, 8}, {0, 8}), wall({0, 8}, {0, 0});
    wall({5, 3}, {6, 3}), wall({6, 3}, {6, 4}), wall({6, 4}, {5, 4}), wall({5, 4}, {5, 3});
    return points;
}

/// Where a room's points are, in the frame of a map whose origin sits at `T_room_map` in the room.
std::vector<Eigen::Vector3f> SeenFrom(const Eigen::Isometry3d& T_room_map) {
    std::vector<Eigen::Vector3f> points;
    for (const auto& p : Room()) points.push_back((T_room_map.inverse() * p.cast<double>()).cast<float>());
    return points;
}

const auto kNever = [](int, int) { return false; };

TEST(MapOverlap, FootprintHoldsEachOccupiedCellOnce) {
    const auto footprint = MapFootprint(Room(), 1.0);
    // 40 m of outer wall through 1 m cells (corners shared) plus the pillar's cell.
    EXPECT_GE(footprint.size(), 40u);
    EXPECT_LE(footprint.size(), 46u);
    for (std::size_t a = 0; a < footprint.size(); ++a)
        for (std::size_t b = 0; b < a; ++b) EXPECT_GT((footprint[a] - footprint[b]).norm(), 0.5);
    EXPECT_EQ(MapFootprint(Room(), 1.0), footprint);  // deterministic
}

TEST(MapOverlap, ALongStraightWallKeepsBoundedMemory) {
    // 200,000 cells in one row (a 20 km wall at 10 cm): cells that differ in one coordinate only must
    // still spread over the hash table (an integer key with the row in its low bits made robin_map grow
    // until the machine ran out of memory on a real walk).
    std::vector<Eigen::Vector3f> wall;
    for (int k = 0; k < 200000; ++k) wall.emplace_back(0.1f * float(k) + 0.05f, 3.05f, 0.0f);
    const auto footprint = MapFootprint(wall, 0.1);
    EXPECT_EQ(footprint.size(), wall.size());
    const auto pairs = PredictOverlaps({footprint, footprint}, {Eigen::Isometry3d::Identity(), Eigen::Isometry3d::Identity()},
                                       0.1, 0.3, 3, kNever);
    ASSERT_EQ(pairs.size(), 1u);
    EXPECT_GT(pairs[0].overlap, 0.99);
}

TEST(MapOverlap, MapsThePosesLayOverEachOtherArePairedAndOthersAreNot) {
    // Map 0 and map 2 see the same room from different origins; map 1 a room 30 m away.
    const Eigen::Isometry3d T_room_0 = PoseFromXYZRPY(1, 1, 0, 0, 0, 0.3);
    const Eigen::Isometry3d T_room_2 = PoseFromXYZRPY(10, 6, 0, 0, 0, -2.0);
    const double cell = 0.5;
    const std::vector<std::vector<Eigen::Vector2d>> footprints = {MapFootprint(SeenFrom(T_room_0), cell),
                                                                  MapFootprint(SeenFrom(T_room_0), cell),
                                                                  MapFootprint(SeenFrom(T_room_2), cell)};
    const Eigen::Isometry3d T_world_room = PoseFromXYZRPY(100, -50, 0, 0, 0, 1.0);
    const Poses right = {T_world_room * T_room_0, PoseFromXYZRPY(30, 0, 0, 0, 0, 0) * T_world_room * T_room_0,
                         T_world_room * T_room_2};
    const auto pairs = PredictOverlaps(footprints, right, cell, 0.3, 5, kNever);
    ASSERT_EQ(pairs.size(), 1u);
    EXPECT_EQ(pairs[0].query, 2);
    EXPECT_EQ(pairs[0].ref, 0);
    EXPECT_GT(pairs[0].overlap, 0.6);  // cell boundaries cut the walls differently in each frame

    // Placed 4 m off (an estimate that drifted that much), the same maps no longer overlap enough.
    Poses drifted = right;
    drifted[2] = PoseFromXYZRPY(3, 2.5, 0, 0, 0, 0) * right[2];
    EXPECT_TRUE(PredictOverlaps(footprints, drifted, cell, 0.3, 5, kNever).empty());
    // A pair the caller refuses (e.g. already joined) is left out.
    EXPECT_TRUE(PredictOverlaps(footprints, right, cell, 0.3, 5, [](int q, int r) { return q == 2 && r == 0; }).empty());
}

TEST(MapOverlap, EachQueryKeepsItsLargestOverlapsUpToTheCap) {
    // Five maps of one room; map 4 overlaps all four earlier ones, map 3 three, and so on.
    const double cell = 0.5;
    std::vector<std::vector<Eigen::Vector2d>> footprints;
    Poses poses;
    for (int m = 0; m < 5; ++m) {
        const Eigen::Isometry3d T_room_map = PoseFromXYZRPY(2 + m, 2, 0, 0, 0, 0.4 * m);
        footprints.push_back(MapFootprint(SeenFrom(T_room_map), cell));
        poses.push_back(T_room_map);
    }
    const auto pairs = PredictOverlaps(footprints, poses, cell, 0.3, 2, kNever);
    // Query 1: one earlier map; queries 2, 3 and 4: their two best, best first.
    ASSERT_EQ(pairs.size(), 7u);
    EXPECT_EQ(pairs[0].query, 1);
    for (std::size_t k = 1; k < pairs.size(); k += 2) {
        EXPECT_EQ(pairs[k].query, pairs[k + 1].query);
        EXPECT_GE(pairs[k].overlap, pairs[k + 1].overlap);
    }
}

}  // namespace
}  // namespace revisit
