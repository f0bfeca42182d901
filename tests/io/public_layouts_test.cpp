#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>

#include "core/error.hpp"
#include "core/pose_interpolation.hpp"
#include "io/reader.hpp"
#include "io/trajectory_io.hpp"
#include "layout_fixtures.hpp"

namespace revisit {
namespace {
namespace fs = std::filesystem;

constexpr std::uint64_t kStart = 1566535000000000000ull;  ///< [ns] a MulRan-like clock

/// The first `n` kitti00_first16 scans laid out as MulRan: sensor_data/Ouster/<ns>.bin and a
/// global_pose.csv at twice the scan rate (poses between scans interpolated), offset by UTM-like metres.
void MakeMulRan(const fs::path& root, std::size_t n, std::size_t first_pose_scan = 0) {
    const auto kitti = test::SharedData("kitti00_first16");
    const auto sample = test::LoadKittiSample(n);
    fs::create_directories(root / "sensor_data" / "Ouster");
    for (std::size_t i = 0; i < n; ++i) {
        char kitti_name[16];
        std::snprintf(kitti_name, sizeof kitti_name, "%06zu.bin", i);
        fs::copy_file(kitti / "velodyne" / kitti_name,
                      root / "sensor_data" / "Ouster" / (std::to_string(kStart + std::llround(sample.times[i] * 1e9)) + ".bin"));
    }
    std::ofstream csv(root / "global_pose.csv");
    for (const auto& [t, T] : test::TwiceRatePoses(sample, first_pose_scan)) {
        csv << kStart + static_cast<std::uint64_t>(std::llround(t * 1e9));
        for (int r = 0; r < 3; ++r) {
            for (int c = 0; c < 4; ++c) {
                char value[40];
                std::snprintf(value, sizeof value, ",%.9f", T(r, c) + (c == 3 && r < 2 ? 350000.0 * (r + 1) : 0.0));
                csv << value;
            }
        }
        csv << '\n';
    }
}

TEST(MulRanLayout, ScansByStampAndReferencePairedByTime) {
    const auto kitti = test::SharedData("kitti00_first16");
    REVISIT_REQUIRE_DATA(kitti);
    test::TempDir dir;
    MakeMulRan(dir / "KAIST01", 6);
    auto reader = OpenDataset(dir / "KAIST01");
    EXPECT_EQ(reader->Info().format, "mulran");
    EXPECT_TRUE(reader->Info().has_reference_poses);
    const auto sample = test::LoadKittiSample(6);
    const auto& times = sample.times;
    const auto& poses = sample.poses;  // the LiDAR's, as the fixture wrote them
    auto original = OpenDataset(kitti);
    for (std::size_t i = 0; i < 6; ++i) {
        const auto scan = reader->Next();
        const auto expected = original->Next();
        ASSERT_TRUE(scan && expected);
        EXPECT_EQ(scan->points, expected->points) << i;
        EXPECT_NEAR(scan->timestamp - static_cast<double>(kStart) * 1e-9, times[i], 1e-6) << i;
        ASSERT_TRUE(scan->T_world_sensor) << i;
        // The file's poses, moved so that the first is at the origin.
        const Eigen::Vector3d expected_position = poses[i].translation() - poses[0].translation();
        EXPECT_LT((scan->T_world_sensor->translation() - expected_position).norm(), 1e-5) << i;
        EXPECT_LT((scan->T_world_sensor->linear() - poses[i].linear()).norm(), 1e-6) << i;
    }
    EXPECT_FALSE(reader->Next());
}

TEST(MulRanLayout, ScansBeforeTheFirstPoseHaveNoneAndBadLinesAreNamed) {
    const auto kitti = test::SharedData("kitti00_first16");
    REVISIT_REQUIRE_DATA(kitti);
    test::TempDir dir;
    MakeMulRan(dir / "seq", 4, 2);  // poses from scan 2 on
    auto reader = OpenDataset(dir / "seq");
    std::vector<bool> has_pose;
    while (auto scan = reader->Next()) has_pose.push_back(scan->T_world_sensor.has_value());
    EXPECT_EQ(has_pose, (std::vector<bool>{false, false, true, true}));
    std::ofstream(dir / "seq" / "global_pose.csv", std::ios::app) << "1566535000000000000,1,0,0\n";
    try {
        OpenDataset(dir / "seq");
        FAIL() << "a short global_pose.csv line was accepted";
    } catch (const DatasetError& e) {
        EXPECT_NE(std::string(e.what()).find("global_pose.csv:4: malformed MulRan pose"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace revisit
