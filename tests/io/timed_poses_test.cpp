#include <gtest/gtest.h>

#include "core/se3.hpp"
#include "io/timed_poses.hpp"

namespace revisit {
namespace {

/// Poses at 1.0, 1.1, ..., 1.9 s plus one after a 2 s gap (at 3.9 s), moving 1 m per 0.1 s along x.
Trajectory TenHertzWithAGap() {
    Trajectory t;
    for (int i = 0; i < 10; ++i) {
        t.timestamps.push_back(1.0 + 0.1 * i);
        t.poses.push_back(PoseFromXYZRPY(i, 0, 0, 0, 0, 0.05 * i));
    }
    t.timestamps.push_back(3.9);
    t.poses.push_back(PoseFromXYZRPY(29, 0, 0, 0, 0, 0));
    return t;
}

TEST(TimedPoses, DefaultsFollowTheMedianSpacing) {
    const TimedPoses poses(TenHertzWithAGap(), {});
    EXPECT_NEAR(poses.end_tolerance(), 0.05, 1e-9);
    EXPECT_NEAR(poses.max_gap(), 0.5, 1e-9);
    const TimedPoses given(TenHertzWithAGap(), {0.2, 3.0});
    EXPECT_DOUBLE_EQ(given.end_tolerance(), 0.2);
    EXPECT_DOUBLE_EQ(given.max_gap(), 3.0);
}

TEST(TimedPoses, InterpolatesBetweenNeighbours) {
    const TimedPoses poses(TenHertzWithAGap(), {});
    const auto at = poses.At(1.325);
    ASSERT_TRUE(at);
    EXPECT_NEAR(at->translation().x(), 3.25, 1e-9);
    EXPECT_NEAR(RotationAngle(*at), 0.05 * 3.25, 1e-9);
    const auto exact = poses.At(1.5);
    ASSERT_TRUE(exact);
    EXPECT_NEAR(exact->translation().x(), 5.0, 1e-9);
}

TEST(TimedPoses, EndsWithinTheToleranceTakeTheEndPose) {
    const TimedPoses poses(TenHertzWithAGap(), {});
    const auto before = poses.At(0.96);
    ASSERT_TRUE(before);
    EXPECT_NEAR(before->translation().x(), 0.0, 1e-12);  // not extrapolated
    EXPECT_FALSE(poses.At(0.94));
    EXPECT_TRUE(poses.At(3.94));
    EXPECT_FALSE(poses.At(3.96));
}

TEST(TimedPoses, NothingInsideAGap) {
    const TimedPoses poses(TenHertzWithAGap(), {});
    EXPECT_FALSE(poses.At(2.5));  // 1.9 .. 3.9 is 2 s > 0.5 s
    EXPECT_TRUE(poses.At(1.9));
    EXPECT_TRUE(poses.At(3.9));
    const TimedPoses wide(TenHertzWithAGap(), {0.0, 2.5});
    const auto inside = wide.At(2.9);
    ASSERT_TRUE(inside);
    EXPECT_NEAR(inside->translation().x(), 19.0, 1e-9);
}

TEST(TimedPoses, RepeatedStampsAndMedian) {
    EXPECT_DOUBLE_EQ(MedianSpacing({}), 0.0);
    EXPECT_DOUBLE_EQ(MedianSpacing({5.0, 5.0}), 0.0);
    EXPECT_NEAR(MedianSpacing({0.0, 0.1, 0.1, 0.3, 1.3}), 0.2, 1e-12);
    Trajectory t;
    t.timestamps = {0.0, 0.0, 1.0};
    t.poses = {PoseFromXYZRPY(0, 0, 0, 0, 0, 0), PoseFromXYZRPY(1, 0, 0, 0, 0, 0), PoseFromXYZRPY(2, 0, 0, 0, 0, 0)};
    const TimedPoses poses(t, {});
    ASSERT_TRUE(poses.At(0.5));
    EXPECT_NEAR(poses.At(0.5)->translation().x(), 1.5, 1e-12);  // from the later of the equal stamps
}

TEST(UnpairedScans, NamesTheCountAndTheFirstAndLast) {
    UnpairedScans unpaired;
    EXPECT_EQ(unpaired.Describe(), "");
    unpaired.Add(0, 0.0);
    unpaired.Add(1, 0.1);
    unpaired.Add(15, 1.5);
    const std::string line = unpaired.Describe();
    EXPECT_NE(line.find("3 scans have no reference pose"), std::string::npos) << line;
    EXPECT_NE(line.find("first scan 0 at t = 0 s"), std::string::npos) << line;
    EXPECT_NE(line.find("last scan 15 at t = 1.5 s"), std::string::npos) << line;
}

}  // namespace
}  // namespace revisit
