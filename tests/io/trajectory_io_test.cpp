#include <gtest/gtest.h>

#include <fstream>

#include "core/error.hpp"
#include "core/se3.hpp"
#include "io/trajectory_io.hpp"
#include "test_data.hpp"

namespace revisit {
namespace {

Trajectory MakeTrajectory() {
    Trajectory t;
    for (int i = 0; i < 20; ++i) {
        t.timestamps.push_back(100.0 + 0.1 * i);
        t.poses.push_back(PoseFromXYZRPY(i * 1.5, -0.2 * i, 0.01 * i, 0.01 * i, -0.02 * i, 0.15 * i));
    }
    return t;
}

void ExpectSamePoses(const Poses& a, const Poses& b, double tolerance) {
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t i = 0; i < a.size(); ++i) EXPECT_LT((a[i].matrix() - b[i].matrix()).norm(), tolerance) << i;
}

void WriteText(const std::filesystem::path& file, const std::string& text) { std::ofstream(file) << text; }

TEST(TrajectoryIo, KittiRoundTrip) {
    test::TempDir dir;
    const auto t = MakeTrajectory();
    WriteKittiPoses(dir / "p.txt", t.poses);
    const auto back = ReadKittiPoses(dir / "p.txt");
    ExpectSamePoses(t.poses, back.poses, 1e-8);
    EXPECT_TRUE(back.timestamps.empty());
}

TEST(TrajectoryIo, TumRoundTripKeepsTimestamps) {
    test::TempDir dir;
    const auto t = MakeTrajectory();
    WriteTumPoses(dir / "p.tum", t);
    const auto back = ReadTumPoses(dir / "p.tum");
    ExpectSamePoses(t.poses, back.poses, 1e-8);
    ASSERT_EQ(back.timestamps.size(), t.timestamps.size());
    EXPECT_NEAR(back.timestamps[7], t.timestamps[7], 1e-9);
}

TEST(TrajectoryIo, AsStoredPosesAreBitForBitWhatTheFilesReadBack) {
    // The evaluation's pass in the chain makes its voxel sets under AsStoredTumPose and the evaluation
    // reads the reference back from a TUM file: the two must agree in every bit, not within a tolerance.
    test::TempDir dir;
    Trajectory t = MakeTrajectory();
    t.timestamps.push_back(102.0);
    t.poses.push_back(PoseFromXYZRPY(-123456.123456789123, 0.5e-10, 7.0, 3.1, -1.5, -3.14159));
    WriteTumPoses(dir / "p.tum", t);
    WriteKittiPoses(dir / "p.txt", t.poses);
    const Poses tum = ReadTumPoses(dir / "p.tum").poses, kitti = ReadKittiPoses(dir / "p.txt").poses;
    ASSERT_EQ(tum.size(), t.size());
    std::size_t moved = 0;
    for (std::size_t i = 0; i < t.size(); ++i) {
        EXPECT_TRUE(AsStoredTumPose(t.poses[i]).matrix() == tum[i].matrix()) << i;
        EXPECT_TRUE(AsStoredKittiPose(t.poses[i]).matrix() == kitti[i].matrix()) << i;
        moved += !(AsStoredTumPose(t.poses[i]).matrix() == t.poses[i].matrix());
    }
    EXPECT_GT(moved, 0u);  // 9 decimals do change most poses: the round trip is not the identity
}

TEST(TrajectoryIo, ReadPosesDetectsTheFormat) {
    test::TempDir dir;
    const auto t = MakeTrajectory();
    WriteKittiPoses(dir / "k.txt", t.poses);
    WriteTumPoses(dir / "t.txt", t);
    EXPECT_FALSE(ReadPoses(dir / "k.txt").has_timestamps());
    EXPECT_TRUE(ReadPoses(dir / "t.txt").has_timestamps());
}

TEST(TrajectoryIo, TumSkipsCommentsAndBlankLines) {
    test::TempDir dir;
    WriteText(dir / "t.txt", "# timestamp tx ty tz qx qy qz qw\n\n1.0 1 2 3 0 0 0 1\n2.0 4 5 6 0 0 0.7071068 0.7071068\n");
    const auto t = ReadTumPoses(dir / "t.txt");
    ASSERT_EQ(t.size(), 2u);
    EXPECT_NEAR(t.poses[1].translation().y(), 5.0, 1e-12);
    EXPECT_NEAR(LogSO3(t.poses[1].linear()).z(), M_PI / 2, 1e-6);
}

TEST(TrajectoryIo, MalformedLineNamesFileAndLine) {
    test::TempDir dir;
    WriteText(dir / "bad.txt", "1 0 0 0 0 1 0 0 0 0 1 0\n1 0 0 0 0 1 0 zero 0 0 1 0\n");
    try {
        ReadKittiPoses(dir / "bad.txt");
        FAIL() << "expected DatasetError";
    } catch (const DatasetError& e) {
        EXPECT_EQ(e.line(), 2u);
        EXPECT_NE(std::string(e.what()).find("bad.txt:2"), std::string::npos) << e.what();
    }
}

TEST(TrajectoryIo, RejectsNonRotationsMissingFilesAndWrongWidths) {
    test::TempDir dir;
    WriteText(dir / "scaled.txt", "2 0 0 0 0 2 0 0 0 0 2 0\n");
    EXPECT_THROW(ReadKittiPoses(dir / "scaled.txt"), DatasetError);
    EXPECT_THROW(ReadKittiPoses(dir / "missing.txt"), DatasetError);
    WriteText(dir / "seven.txt", "1 2 3 4 5 6 7\n");
    EXPECT_THROW(ReadPoses(dir / "seven.txt"), DatasetError);
    WriteText(dir / "nan.txt", "1.0 nan 2 3 0 0 0 1\n");
    EXPECT_THROW(ReadTumPoses(dir / "nan.txt"), DatasetError);
    WriteText(dir / "back.txt", "2.0 0 0 0 0 0 0 1\n1.0 0 0 0 0 0 0 1\n");
    EXPECT_THROW(ReadTumPoses(dir / "back.txt"), DatasetError);
}

TEST(TrajectoryIo, AssociateByTimePicksNearestWithinTolerance) {
    const std::vector<double> reference{0.0, 0.1, 0.2, 0.3};
    const auto idx = AssociateByTime(reference, {-0.5, 0.04, 0.16, 0.31, 0.9}, 0.05);
    EXPECT_EQ(idx, (std::vector<long>{-1, 0, 2, 3, -1}));
}

}  // namespace
}  // namespace revisit
