#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>

#include "cli.hpp"
#include "core/error.hpp"
#include "io/reader.hpp"
#include "layout_fixtures.hpp"

namespace revisit {
namespace {
namespace fs = std::filesystem;

constexpr std::uint64_t kNewerCollegeStart = 1583836591182590976ull;  ///< [ns] a Newer College 2020 clock
constexpr std::uint64_t kNcltStart = 1326030975726043ull;             ///< [us] an NCLT (2012-01-08) clock

std::string Stamp(std::uint64_t value) { return std::to_string(value); }

/// Newer College 2020: raw_format/ouster_scan/cloud_<sec>_<nsec>.pcd (binary PCD, x y z intensity) and
/// ground_truth/registered_poses.csv (#sec,nsec,x,y,z,qx,qy,qz,qw) at twice the scan rate.
void MakeNewerCollege(const fs::path& root, const test::KittiSample& sample) {
    for (std::size_t i = 0; i < sample.scans.size(); ++i) {
        const std::uint64_t ns = kNewerCollegeStart + static_cast<std::uint64_t>(std::llround(sample.times[i] * 1e9));
        char name[64];
        std::snprintf(name, sizeof name, "cloud_%llu_%09llu.pcd", static_cast<unsigned long long>(ns / 1000000000ull),
                      static_cast<unsigned long long>(ns % 1000000000ull));
        const Scan& scan = sample.scans[i];
        std::string pcd = "# .PCD v0.7\nVERSION 0.7\nFIELDS x y z intensity\nSIZE 4 4 4 4\nTYPE F F F F\nCOUNT 1 1 1 1\nWIDTH " +
                          std::to_string(scan.points.size()) + "\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS " +
                          std::to_string(scan.points.size()) + "\nDATA binary\n";
        for (std::size_t p = 0; p < scan.points.size(); ++p) {
            for (int c = 0; c < 3; ++c) test::AppendRaw(pcd, scan.points[p][c]);
            test::AppendRaw(pcd, scan.intensities[p]);
        }
        test::WriteBytes(root / "raw_format" / "ouster_scan" / name, pcd);
    }
    fs::create_directories(root / "ground_truth");
    std::ofstream csv(root / "ground_truth" / "registered_poses.csv");
    csv << "#sec,nsec,x,y,z,qx,qy,qz,qw\n";
    for (const auto& [t, T] : test::TwiceRatePoses(sample)) {
        const std::uint64_t ns = kNewerCollegeStart + static_cast<std::uint64_t>(std::llround(t * 1e9));
        const Eigen::Quaterniond q(T.linear());
        char line[256];
        std::snprintf(line, sizeof line, "%llu, %llu, %.9f, %.9f, %.9f, %.12f, %.12f, %.12f, %.12f\n",
                      static_cast<unsigned long long>(ns / 1000000000ull), static_cast<unsigned long long>(ns % 1000000000ull),
                      T.translation().x(), T.translation().y(), T.translation().z(), q.x(), q.y(), q.z(), q.w());
        csv << line;
    }
}

/// NCLT's frames have z down: the same 180-degree turn about x as the reader's, written out.
Eigen::Isometry3d Flip(const Eigen::Isometry3d& T) {
    Eigen::Isometry3d F = Eigen::Isometry3d::Identity();
    F.linear() = Eigen::Vector3d(1, -1, -1).asDiagonal();
    return F * T * F;
}

std::uint16_t NcltCount(float metres) { return static_cast<std::uint16_t>(std::lround((metres + 100.0) / 0.005)); }

/// NCLT: SESSION/velodyne_sync/<us>.bin (uint16 x, y, z scaled, uint8 intensity, uint8 laser) in the
/// z-down frame, and ground_truth/groundtruth_SESSION.csv (utime, x, y, z, roll, pitch, yaw) at twice
/// the scan rate, led by a row of NaN as the published files are.
void MakeNclt(const fs::path& root, const test::KittiSample& sample) {
    const fs::path session = root / "2012-01-08";
    for (std::size_t i = 0; i < sample.scans.size(); ++i) {
        std::string bin;
        const Scan& scan = sample.scans[i];
        for (std::size_t p = 0; p < scan.points.size(); ++p) {
            const Eigen::Vector3f& q = scan.points[p];
            test::AppendRaw(bin, NcltCount(q.x()));
            test::AppendRaw(bin, NcltCount(-q.y()));
            test::AppendRaw(bin, NcltCount(-q.z()));
            test::AppendRaw(bin, static_cast<std::uint8_t>(std::lround(scan.intensities[p] * 255.f)));
            test::AppendRaw(bin, static_cast<std::uint8_t>(p % 32));
        }
        const std::uint64_t us = kNcltStart + static_cast<std::uint64_t>(std::llround(sample.times[i] * 1e6));
        test::WriteBytes(session / "velodyne_sync" / (Stamp(us) + ".bin"), bin);
    }
    fs::create_directories(root / "ground_truth");
    std::ofstream csv(root / "ground_truth" / "groundtruth_2012-01-08.csv");
    csv << Stamp(kNcltStart - 50000) << ",nan,nan,nan,nan,nan,nan\n";
    for (const auto& [t, T_up] : test::TwiceRatePoses(sample)) {
        const Eigen::Isometry3d T = Flip(T_up);
        const Eigen::Vector3d ypr = T.linear().eulerAngles(2, 1, 0);  // R = Rz(yaw) Ry(pitch) Rx(roll)
        char line[256];
        std::snprintf(line, sizeof line, "%llu,%.9f,%.9f,%.9f,%.12f,%.12f,%.12f\n",
                      static_cast<unsigned long long>(kNcltStart + std::llround(t * 1e6)), T.translation().x(),
                      T.translation().y(), T.translation().z(), ypr[2], ypr[1], ypr[0]);
        csv << line;
    }
}

void ExpectPosesNear(const Eigen::Isometry3d& actual, const Eigen::Isometry3d& expected, std::size_t i) {
    EXPECT_LT((actual.translation() - expected.translation()).norm(), 1e-5) << i;
    EXPECT_LT((actual.linear() - expected.linear()).norm(), 1e-6) << i;
}

std::string ErrorOf(const std::function<void()>& action) {
    try {
        action();
    } catch (const DatasetError& e) {
        return e.what();
    }
    return "(no error)";
}

TEST(NewerCollegeLayout, ScansByStampAndRegisteredPosesPairedByTime) {
    REVISIT_REQUIRE_DATA(test::SharedData("kitti00_first16"));
    const auto sample = test::LoadKittiSample(5);
    test::TempDir dir;
    MakeNewerCollege(dir / "01_short_experiment", sample);
    auto reader = OpenDataset(dir / "01_short_experiment");
    EXPECT_EQ(reader->Info().format, "newer college");
    EXPECT_EQ(reader->Info().poses_file.filename(), "registered_poses.csv");
    for (std::size_t i = 0; i < sample.scans.size(); ++i) {
        const auto scan = reader->Next();
        ASSERT_TRUE(scan) << i;
        EXPECT_EQ(scan->points, sample.scans[i].points) << i;
        EXPECT_EQ(scan->intensities, sample.scans[i].intensities) << i;
        EXPECT_NEAR(scan->timestamp - kNewerCollegeStart * 1e-9, sample.times[i], 1e-6) << i;
        ASSERT_TRUE(scan->T_world_sensor) << i;
        ExpectPosesNear(*scan->T_world_sensor, sample.poses[i], i);
    }
    EXPECT_FALSE(reader->Next());
}

TEST(NewerCollegeLayout, ExtensionGroundTruthAndBadInputAreNamed) {
    REVISIT_REQUIRE_DATA(test::SharedData("kitti00_first16"));
    const auto sample = test::LoadKittiSample(3);
    test::TempDir dir;
    const fs::path root = dir / "quad-easy";
    MakeNewerCollege(root, sample);
    // The 2021 extension names its ground truth gt-nc-<sequence>.csv, same columns.
    fs::rename(root / "ground_truth" / "registered_poses.csv", root / "ground_truth" / "gt-nc-quad-easy.csv");
    auto reader = OpenDataset(root);
    EXPECT_EQ(reader->Info().poses_file.filename(), "gt-nc-quad-easy.csv");
    EXPECT_TRUE(reader->Info().has_reference_poses);
    std::ofstream(root / "ground_truth" / "gt-nc-quad-easy.csv", std::ios::app) << "1583836592,5,1.0,2.0\n";
    EXPECT_NE(ErrorOf([&] { OpenDataset(root); }).find("gt-nc-quad-easy.csv:7: malformed sec,nsec"), std::string::npos);
    fs::remove(root / "ground_truth" / "gt-nc-quad-easy.csv");
    test::WriteBytes(root / "raw_format" / "ouster_scan" / "cloud_15838365.pcd", "x");
    EXPECT_NE(ErrorOf([&] { OpenDataset(root); }).find("cloud_15838365.pcd: the scans of this layout are named cloud_<sec>_<nsec>"),
              std::string::npos);
}

TEST(NcltLayout, ScaledPointsTurnedZUpAndGroundTruthPairedByTime) {
    REVISIT_REQUIRE_DATA(test::SharedData("kitti00_first16"));
    const auto sample = test::LoadKittiSample(5);
    test::TempDir dir;
    MakeNclt(dir.path(), sample);
    auto reader = OpenDataset(dir / "2012-01-08");
    EXPECT_EQ(reader->Info().format, "nclt");
    EXPECT_EQ(reader->Info().poses_file.filename(), "groundtruth_2012-01-08.csv");
    for (std::size_t i = 0; i < sample.scans.size(); ++i) {
        const auto scan = reader->Next();
        ASSERT_TRUE(scan) << i;
        const Scan& expected = sample.scans[i];
        ASSERT_EQ(scan->points.size(), expected.points.size()) << i;
        float worst = 0.f;
        for (std::size_t p = 0; p < expected.points.size(); ++p) {
            worst = std::max(worst, (scan->points[p] - expected.points[p]).cwiseAbs().maxCoeff());
            ASSERT_EQ(scan->intensities[p], std::lround(expected.intensities[p] * 255.f)) << i << " " << p;
        }
        EXPECT_LE(worst, 0.0025f + 1e-4f) << i;  // half of the 5 mm step, plus float rounding
        EXPECT_GT(worst, 0.0f) << i;              // the encoding is lossy: a reader copying floats would not be
        EXPECT_NEAR(scan->timestamp - kNcltStart * 1e-6, sample.times[i], 1e-6) << i;
        ASSERT_TRUE(scan->T_world_sensor) << i;
        ExpectPosesNear(*scan->T_world_sensor, sample.poses[i], i);
    }
    EXPECT_FALSE(reader->Next());
}

TEST(NcltLayout, TruncatedScanAndBadGroundTruthLineAreNamed) {
    REVISIT_REQUIRE_DATA(test::SharedData("kitti00_first16"));
    const auto sample = test::LoadKittiSample(2);
    test::TempDir dir;
    MakeNclt(dir.path(), sample);
    const fs::path session = dir / "2012-01-08";
    const fs::path first = session / "velodyne_sync" / (Stamp(kNcltStart) + ".bin");
    const auto size = fs::file_size(first);
    fs::resize_file(first, size - 5);  // the last point cut short
    auto reader = OpenDataset(session);
    const std::string error = ErrorOf([&] { reader->Next(); });
    EXPECT_NE(error.find(first.filename().string()), std::string::npos) << error;
    EXPECT_NE(error.find("byte offset " + std::to_string(size - 8)), std::string::npos) << error;
    std::ofstream(dir / "ground_truth" / "groundtruth_2012-01-08.csv", std::ios::app) << "1326030975926043,1.0,x,0,0,0,0\n";
    EXPECT_NE(ErrorOf([&] { OpenDataset(session); }).find("groundtruth_2012-01-08.csv:5: malformed NCLT ground truth"),
              std::string::npos);
}

TEST(PublicLayoutsCli, InfoDescribesAndConvertWritesKittiAndRawlog) {
    REVISIT_REQUIRE_DATA(test::SharedData("kitti00_first16"));
    const auto sample = test::LoadKittiSample(4);
    test::TempDir dir;
    MakeNclt(dir.path(), sample);
    const fs::path session = dir / "2012-01-08";
    const auto info = test::RunCli("info " + test::Quote(session.string()));
    EXPECT_EQ(info.exit_code, 0) << info.output;
    EXPECT_NE(info.output.find("nclt"), std::string::npos) << info.output;
    EXPECT_NE(info.output.find("groundtruth_2012-01-08.csv"), std::string::npos) << info.output;
    const auto original = test::ReadAllScans(session);
    for (const std::string out : {"kitti_out", "out.rawlog"}) {
        const auto convert = test::RunCli("convert " + test::Quote(session.string()) + " " + test::Quote((dir / out).string()));
        ASSERT_EQ(convert.exit_code, 0) << convert.output;
        const auto converted = test::ReadAllScans(dir / out);
        ASSERT_EQ(converted.size(), original.size()) << out;
        for (std::size_t i = 0; i < original.size(); ++i) {
            EXPECT_EQ(converted[i].points, original[i].points) << out << " " << i;
            EXPECT_NEAR(converted[i].timestamp, original[i].timestamp, 1e-6) << out << " " << i;
            ASSERT_TRUE(converted[i].T_world_sensor) << out << " " << i;
            ExpectPosesNear(*converted[i].T_world_sensor, *original[i].T_world_sensor, i);
        }
    }
}

}  // namespace
}  // namespace revisit
