#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "core/error.hpp"
#include "core/trajectory.hpp"
#include "io/cloud_files.hpp"
#include "io/reader.hpp"
#include "io/trajectory_io.hpp"
#include "test_data.hpp"

namespace revisit {
namespace {
namespace fs = std::filesystem;

Scan SyntheticScan(int seed, std::size_t n) {
    Scan scan;
    for (std::size_t i = 0; i < n; ++i) {
        scan.points.emplace_back(static_cast<float>(seed + i * 0.5), static_cast<float>(i % 7), -1.5f);
        scan.intensities.push_back(static_cast<float>(i % 3) / 3.f);
    }
    return scan;
}

/// A small KITTI folder: `n` scans, poses moving 1 m along x per scan (camera frame with identity Tr).
void MakeKittiFolder(const fs::path& root, int n) {
    fs::create_directories(root / "velodyne");
    Poses poses;
    for (int i = 0; i < n; ++i) {
        char name[16];
        std::snprintf(name, sizeof(name), "%06d.bin", i);
        SaveKittiBin(root / "velodyne" / name, SyntheticScan(i, 10 + i));
        Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
        T.translation().x() = i;
        poses.push_back(T);
    }
    WriteKittiPoses(root / "poses.txt", poses);
}

TEST(KittiReader, RealSequenceFirst16Scans) {
    const auto folder = test::SharedData("kitti00_first16");
    REVISIT_REQUIRE_DATA(folder);
    auto reader = OpenDataset(folder);
    EXPECT_EQ(reader->Info().format, "kitti");
    ASSERT_EQ(reader->Info().num_scans, 16u);
    Poses poses;
    while (auto scan = reader->Next()) {
        EXPECT_GE(scan->points.size(), 120000u);
        EXPECT_LE(scan->points.size(), 125000u);
        EXPECT_EQ(scan->intensities.size(), scan->points.size());
        ASSERT_TRUE(scan->T_world_sensor.has_value());
        poses.push_back(*scan->T_world_sensor);
    }
    ASSERT_EQ(poses.size(), 16u);
    EXPECT_NEAR(PathLength(poses), 12.9, 0.1);
    // Converted to the LiDAR frame (Tr^-1 P Tr): the car drives along the LiDAR's +x axis.
    EXPECT_NEAR(poses.back().translation().x(), 12.87, 0.1);
    EXPECT_LT(std::abs(poses.back().translation().y()), 1.0);  // a slight drift to the left
    EXPECT_LT(std::abs(poses.back().translation().z()), 0.5);
    EXPECT_EQ(reader->Stats().non_finite_points, 0u);
}

TEST(KittiReader, VerticalCorrectionTiltsPointsByTheDocumentedAngle) {
    test::TempDir dir;
    MakeKittiFolder(dir.path(), 1);
    ReaderOptions options;
    options.kitti_vertical_correction = true;
    const auto plain = OpenDataset(dir.path())->Next();
    const auto corrected = OpenDataset(dir.path(), options)->Next();
    ASSERT_TRUE(plain && corrected);
    const Eigen::Vector3f a = plain->points[5], b = corrected->points[5];
    const double angle = std::acos(a.normalized().dot(b.normalized()));
    EXPECT_NEAR(angle * 180.0 / M_PI, 0.205, 1e-3);
    EXPECT_NEAR(a.norm(), b.norm(), 1e-4);
}

TEST(KittiReader, OfficialLayoutFindsPosesBesideSequences) {
    test::TempDir dir;
    const auto sequence = dir.path() / "sequences" / "07";
    MakeKittiFolder(sequence, 3);
    fs::create_directories(dir.path() / "poses");
    fs::rename(sequence / "poses.txt", dir.path() / "poses" / "07.txt");
    auto reader = OpenDataset(sequence);
    EXPECT_TRUE(reader->Info().has_reference_poses);
    EXPECT_EQ(reader->Info().poses_file, dir.path() / "poses" / "07.txt");
    EXPECT_THROW(OpenDataset(dir.path()), DatasetError);  // the root: must name a sequence
}

TEST(KittiReader, StreamsScansInOrderWithTimesAndPoses) {
    test::TempDir dir;
    MakeKittiFolder(dir.path(), 4);
    WriteTimes(dir / "times.txt", {0.0, 0.11, 0.2, 0.32});
    auto reader = OpenDataset(dir.path());
    for (int i = 0; i < 4; ++i) {
        auto scan = reader->Next();
        ASSERT_TRUE(scan);
        EXPECT_EQ(scan->index, static_cast<std::size_t>(i));
        EXPECT_EQ(scan->points.size(), static_cast<std::size_t>(10 + i));
        EXPECT_NEAR(scan->T_world_sensor->translation().x(), i, 1e-9);
    }
    EXPECT_FALSE(reader->Next());
}

TEST(KittiReader, SkipToGoesToAScanWithoutReadingTheOnesBefore) {
    test::TempDir dir;
    MakeKittiFolder(dir / "seq", 5);
    // Scan 1's file is damaged: a reader that went through it would throw.
    std::ofstream(dir / "seq" / "velodyne" / "000001.bin", std::ios::binary | std::ios::trunc) << "bad";
    auto reader = OpenDataset(dir / "seq");
    ASSERT_TRUE(reader->SkipTo(3));
    EXPECT_EQ(reader->Stats().scans, 3u);
    const auto scan = reader->Next();
    ASSERT_TRUE(scan);
    EXPECT_EQ(scan->index, 3u);
    EXPECT_EQ(scan->points.size(), 13u);
    ASSERT_TRUE(scan->T_world_sensor);
    EXPECT_DOUBLE_EQ(scan->T_world_sensor->translation().x(), 3.0);
    EXPECT_DOUBLE_EQ(scan->timestamp, 0.3);
    ASSERT_TRUE(reader->SkipTo(0));  // already past: nothing moves
    EXPECT_EQ(reader->Next()->index, 4u);
    EXPECT_FALSE(reader->Next());
}

TEST(KittiReader, BinWithBadSizeIsRejectedWithTheFileName) {
    test::TempDir dir;
    MakeKittiFolder(dir.path(), 2);
    const auto bad = dir.path() / "velodyne" / "000001.bin";
    std::ofstream(bad, std::ios::app) << "xyz";
    auto reader = OpenDataset(dir.path());
    EXPECT_TRUE(reader->Next());
    try {
        reader->Next();
        FAIL() << "expected DatasetError";
    } catch (const DatasetError& e) {
        EXPECT_NE(std::string(e.what()).find("000001.bin"), std::string::npos);
        EXPECT_NE(std::string(e.what()).find("multiple of 16"), std::string::npos);
    }
}

TEST(KittiReader, PoseCountMismatchIsAnError) {
    test::TempDir dir;
    MakeKittiFolder(dir.path(), 3);
    WriteKittiPoses(dir / "poses.txt", Poses(2, Eigen::Isometry3d::Identity()));
    try {
        OpenDataset(dir.path());
        FAIL() << "expected DatasetError";
    } catch (const DatasetError& e) {
        EXPECT_NE(std::string(e.what()).find("2 poses for 3 scans"), std::string::npos) << e.what();
    }
}

TEST(KittiReader, NonFinitePointsAreDroppedAndCounted) {
    test::TempDir dir;
    fs::create_directories(dir / "velodyne");
    Scan scan = SyntheticScan(0, 5);
    scan.points[1].x() = std::numeric_limits<float>::quiet_NaN();
    scan.points[3].z() = std::numeric_limits<float>::infinity();
    SaveKittiBin(dir / "velodyne" / "000000.bin", scan);
    auto reader = OpenDataset(dir.path());
    const auto read = reader->Next();
    ASSERT_TRUE(read);
    EXPECT_EQ(read->points.size(), 3u);
    EXPECT_EQ(read->intensities.size(), 3u);
    EXPECT_EQ(reader->Stats().non_finite_points, 2u);
    EXPECT_NE(DescribeDrops(reader->Stats()).find("2 NaN/inf"), std::string::npos);
}

TEST(OpenDataset, MissingOrEmptyPathsAreClearErrors) {
    test::TempDir dir;
    EXPECT_THROW(OpenDataset(""), DatasetError);
    EXPECT_THROW(OpenDataset(dir / "nope"), DatasetError);
    EXPECT_THROW(OpenDataset(dir.path()), DatasetError);  // empty folder: no scans
    std::ofstream(dir / "notes.txt") << "hello";
    EXPECT_THROW(OpenDataset(dir / "notes.txt"), DatasetError);
}

}  // namespace
}  // namespace revisit
