// The evaluation on real data from ../shared (skipped when it is absent): KITTI 00 ground truth
// (3.7 km) and the first 16 real HDL-64E scans of KITTI 00.
#include "core/se3.hpp"
#include "evaluation/ground_truth_closures.hpp"
#include "evaluation/scan_context.hpp"
#include "evaluation/trajectory_metrics.hpp"
#include "io/trajectory_io.hpp"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace revisit {
namespace {

const std::filesystem::path kData = std::filesystem::path(REVISIT_SHARED_DIR) / "data";

#define SKIP_WITHOUT_SHARED_DATA()                                                   \
    if (!std::filesystem::exists(REVISIT_SHARED_DIR)) {                              \
        GTEST_SKIP() << "no shared data folder at " << REVISIT_SHARED_DIR;           \
    }

std::vector<Eigen::Vector3f> ReadKittiBin(const std::filesystem::path& file) {
    std::vector<float> values(4 * 200000);
    std::FILE* stream = std::fopen(file.c_str(), "rb");
    if (!stream) return {};
    const std::size_t count = std::fread(values.data(), sizeof(float), values.size(), stream);
    std::fclose(stream);
    std::vector<Eigen::Vector3f> points;
    for (std::size_t k = 0; k + 3 < count; k += 4) points.emplace_back(values[k], values[k + 1], values[k + 2]);
    return points;
}

/// Velodyne-frame poses: T_lidar = Tr^-1 * P * Tr (DATA.md).
Poses LidarPoses(const std::filesystem::path& folder) {
    std::ifstream calib(folder / "calib.txt");
    Eigen::Isometry3d Tr = Eigen::Isometry3d::Identity();
    for (std::string line; std::getline(calib, line);) {
        if (line.rfind("Tr:", 0) != 0) continue;
        std::istringstream fields(line.substr(3));
        for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 4; ++c) fields >> Tr.matrix()(r, c);
    }
    Poses poses;
    for (const auto& P : ReadKittiPoses(folder / "poses.txt").poses) poses.push_back(Tr.inverse() * P * Tr);
    return poses;
}

TEST(RealData, ApeOfKitti00UnderARigidMisalignmentIsZero) {
    SKIP_WITHOUT_SHARED_DATA();
    const Poses reference = ReadKittiPoses(kData / "kitti_gt_poses/00.txt").poses;
    ASSERT_EQ(reference.size(), 4541u);
    const Eigen::Isometry3d T_est_ref = PoseFromXYZRPY(100.0, -20.0, 5.0, 0.05, -0.03, 2.0);
    Poses moved;
    for (const auto& T : reference) moved.push_back(T_est_ref * T);
    const auto ape = ComputeApe(moved, reference);
    EXPECT_LT(ape.errors.translation_stats.max, 1e-6);
    EXPECT_LT(ape.errors.rotation_deg_stats.max, 1e-4);  // the file's rotations have ~7 digits
}

TEST(RealData, KittiSegmentErrorsOfAScaledKitti00) {
    SKIP_WITHOUT_SHARED_DATA();
    const Poses reference = ReadKittiPoses(kData / "kitti_gt_poses/00.txt").poses;
    Poses scaled;
    for (auto T : reference) {
        T.translation() *= 1.02;
        scaled.push_back(T);
    }
    const auto errors = ComputeKittiErrors(scaled, reference);
    // A 2% scale error: error = 2% of the chord, and chord / path length <= 1: at most 2%, close to it on
    // 100 m segments (mostly straight), less on 800 m ones (city blocks turn).
    EXPECT_GT(errors.num_segments, 2000u);
    EXPECT_LT(errors.translation_percent, 2.0 + 1e-9);
    EXPECT_GT(errors.translation_percent, 1.0);
    EXPECT_GT(errors.per_length.front().translation_percent, 1.8);
    EXPECT_LT(errors.per_length.back().translation_percent, errors.per_length.front().translation_percent);
    EXPECT_NEAR(errors.rotation_deg_per_100m, 0.0, 1e-6);
    // An unaligned rigid misalignment leaves relative errors unchanged: 0.
    Poses moved;
    for (const auto& T : reference) moved.push_back(PoseFromXYZRPY(3, 4, 5, 0.1, 0.2, 0.3) * T);
    EXPECT_NEAR(ComputeKittiErrors(moved, reference).translation_percent, 0.0, 1e-6);
    EXPECT_NEAR(ComputeRpe(moved, reference).translation_stats.max, 0.0, 1e-6);
}

TEST(RealData, OverlapOfRealScansFallsWithDistance) {
    SKIP_WITHOUT_SHARED_DATA();
    const auto folder = kData / "kitti00_first16";
    const Poses poses = LidarPoses(folder);
    ASSERT_EQ(poses.size(), 16u);
    std::vector<std::vector<Eigen::Vector3f>> scans;
    for (int i = 0; i < 16; ++i) {
        char name[32];
        std::snprintf(name, sizeof(name), "%06d.bin", i);
        scans.push_back(ReadKittiBin(folder / "velodyne" / name));
        ASSERT_GT(scans.back().size(), 100000u);
    }
    // Compare every segment with every later one (tiny travel gap) to see the overlap against distance.
    GtClosureConfig config;
    config.travel_gap_ranges = 1e-3;
    config.min_overlap = 0.0;
    const auto closures = ComputeGroundTruthClosures(poses, [&](std::size_t i) { return scans[i]; }, config);
    ASSERT_GE(closures.segments.size(), 6u);  // ~0.86 m per scan: 2-3 scans per 2 m segment
    double next = 0.0, far = 1.0;
    for (const auto& pair : closures.segment_pairs) {
        if (pair.earlier != 0) continue;
        if (pair.later == 1) next = pair.overlap;
        if (pair.later + 1 == closures.segments.size()) far = pair.overlap;
    }
    EXPECT_GT(next, 0.5);   // 2 m apart: most voxels seen again
    EXPECT_LT(far, next);   // ~12 m apart: fewer
    EXPECT_GT(far, 0.1);    // but the same street
}

TEST(RealData, ScanContextOfRealScans) {
    SKIP_WITHOUT_SHARED_DATA();
    const auto folder = kData / "kitti00_first16/velodyne";
    const ScanContextConfig config;
    const auto scan0 = ReadKittiBin(folder / "000000.bin");
    const auto scan1 = ReadKittiBin(folder / "000001.bin");
    const auto scan15 = ReadKittiBin(folder / "000015.bin");
    const auto d0 = MakeScanContext(scan0, config);
    const double next = ScanContextDistance(MakeScanContext(scan1, config), d0, config).distance;
    const double far = ScanContextDistance(MakeScanContext(scan15, config), d0, config).distance;
    EXPECT_LT(next, far);  // 0.86 m vs 12 m apart
    // The same scan turned by 90 degrees (15 sectors) is found at shift 15 with distance ~0.
    const Eigen::Matrix3f R = Eigen::AngleAxisf(static_cast<float>(M_PI / 2 + 1e-4), Eigen::Vector3f::UnitZ()).toRotationMatrix();
    std::vector<Eigen::Vector3f> turned;
    for (const auto& p : scan0) turned.push_back(R * p);
    const auto match = ScanContextDistance(MakeScanContext(turned, config), d0, config);
    EXPECT_EQ(match.shift, 15);
    EXPECT_LT(match.distance, 0.01);
}

}  // namespace
}  // namespace revisit
