#include "evaluation/segment_voxel_file.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <random>
#include <vector>

#include "evaluation/ground_truth_closures.hpp"
#include "test_data.hpp"

namespace revisit {
namespace {

/// A drive with stops, slow and fast stretches and turns: segments of one scan and of many.
Poses Drive(std::size_t count) {
    Poses poses;
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    for (std::size_t k = 0; k < count; ++k) {
        const double speed = (k / 40) % 3 == 0 ? 0.0 : ((k / 40) % 3 == 1 ? 0.37 : 2.9);  // [m] per scan
        Eigen::Isometry3d step = Eigen::Isometry3d::Identity();
        step.translation() = Eigen::Vector3d(speed, 0.0, 0.01 * std::sin(0.1 * double(k)));
        step.linear() = Eigen::AngleAxisd(0.03 * std::sin(0.05 * double(k)), Eigen::Vector3d::UnitZ()).toRotationMatrix();
        T = T * step;
        poses.push_back(T);
    }
    return poses;
}

std::vector<Eigen::Vector3f> Points(std::mt19937& rng) {
    std::uniform_real_distribution<float> uniform(-20.0f, 20.0f);
    std::vector<Eigen::Vector3f> points;
    for (int k = 0; k < 3000; ++k) points.emplace_back(uniform(rng), uniform(rng), uniform(rng) / 10.0f);
    return points;
}

TEST(SegmentVoxelFile, HoldsTheSegmentsAndSetsOfAPassOverTheScans) {
    const test::TempDir dir;
    const Poses poses = Drive(300);
    GtClosureConfig config;
    std::mt19937 rng(5);
    std::vector<std::vector<Eigen::Vector3f>> scans;
    for (std::size_t k = 0; k < poses.size(); ++k) scans.push_back(Points(rng));

    SegmentVoxelFile file(dir / "segments.scratch", config.segment_length);
    for (std::size_t k = 0; k < poses.size(); ++k)
        file.Add(poses[k], ScanVoxels(poses[k], scans[k], config.voxel_size, config.voxel_subsample));
    file.Finish();
    EXPECT_EQ(file.num_scans(), poses.size());

    // The segments CutSegments makes of the whole trajectory, with the sets AddVoxels accumulates.
    const std::vector<GtSegment> expected = CutSegments(poses, config.segment_length);
    ASSERT_EQ(file.segments().size(), expected.size());
    ASSERT_GT(expected.size(), 20u);
    std::size_t multi_scan = 0;
    for (std::size_t s = 0; s < expected.size(); ++s) {
        EXPECT_EQ(file.segments()[s].first_scan, expected[s].first_scan);
        EXPECT_EQ(file.segments()[s].last_scan, expected[s].last_scan);
        EXPECT_EQ(file.segments()[s].start_travel, expected[s].start_travel);
        multi_scan += expected[s].last_scan > expected[s].first_scan;
        PackedVoxels accumulated;
        for (std::size_t k = expected[s].first_scan; k <= expected[s].last_scan; ++k)
            AddVoxels(accumulated, poses[k], scans[k], config.voxel_size, config.voxel_subsample);
        const PackedVoxels loaded = file.Load(s);
        EXPECT_EQ(loaded.bytes, accumulated.bytes) << "segment " << s;
        EXPECT_EQ(loaded.size, accumulated.size) << "segment " << s;
        const VoxelColumns columns = file.LoadColumns(s), expected_columns = ColumnsOf(accumulated);
        EXPECT_EQ(columns.x0, expected_columns.x0);
        EXPECT_EQ(columns.y0, expected_columns.y0);
        EXPECT_EQ(columns.cells, expected_columns.cells);
        EXPECT_EQ(columns.size, accumulated.size);
        EXPECT_EQ(columns.bounded, expected_columns.bounded);
    }
    EXPECT_GT(multi_scan, 5u);  // the stops make long segments
    EXPECT_THROW(file.Load(expected.size()), std::out_of_range);
}

TEST(SegmentVoxelFile, LeavesNothingBehind) {
    const test::TempDir dir;
    {
        SegmentVoxelFile file(dir / "segments.scratch", 2.0);
        std::mt19937 rng(1);
        file.Add(Eigen::Isometry3d::Identity(), ScanVoxels(Eigen::Isometry3d::Identity(), Points(rng), 0.5, 1));
        file.Finish();
        EXPECT_EQ(file.segments().size(), 1u);
        EXPECT_FALSE(std::filesystem::is_empty(dir.path()));
    }
    EXPECT_TRUE(std::filesystem::is_empty(dir.path()));
    EXPECT_THROW(SegmentVoxelFile(dir / "x.scratch", 0.0), std::exception);
}

}  // namespace
}  // namespace revisit
