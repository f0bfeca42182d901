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

void ExpectPosesNear(const Eigen::Isometry3d& actual, const Eigen::Isometry3d& expected, std::size_t i) {
    EXPECT_LT((actual.translation() - expected.translation()).norm(), 1e-5) << i;
    EXPECT_LT((actual.linear() - expected.linear()).norm(), 1e-6) << i;
}

TEST(NewerCollegeLayout, ScansByStampAndRegisteredPosesPairedByTime) {
    REVISIT_REQUIRE_DATA(test::SharedData("kitti00_first16"));
    const auto sample = test::LoadKittiSample(5);
    test::TempDir dir;
    test::MakeNewerCollege(dir / "01_short_experiment", sample);
    auto reader = OpenDataset(dir / "01_short_experiment");
    EXPECT_EQ(reader->Info().format, "newer college");
    EXPECT_EQ(reader->Info().poses_file.filename(), "registered_poses.csv");
    // The same file given with --gt (e.g. beside a 2021 bag) is detected as the sec,nsec CSV.
    const Trajectory gt = ReadPoses(dir / "01_short_experiment" / "ground_truth" / "registered_poses.csv");
    ASSERT_EQ(gt.size(), 2 * sample.scans.size() - 1);
    EXPECT_NEAR(gt.timestamps[2] - test::kNewerCollegeStart * 1e-9, sample.times[1], 1e-6);
    for (std::size_t i = 0; i < sample.scans.size(); ++i) {
        const auto scan = reader->Next();
        ASSERT_TRUE(scan) << i;
        EXPECT_EQ(scan->points, sample.scans[i].points) << i;
        EXPECT_EQ(scan->intensities, sample.scans[i].intensities) << i;
        ASSERT_EQ(scan->point_times.size(), scan->points.size()) << i;
        for (std::size_t p = 0; p < scan->points.size(); p += 101) {
            EXPECT_NEAR(scan->point_times[p], test::PointTime(p), 1e-7) << i << " " << p;  // the Ouster's ns, as seconds
        }
        EXPECT_NEAR(scan->timestamp - test::kNewerCollegeStart * 1e-9, sample.times[i], 1e-6) << i;
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
    test::MakeNewerCollege(root, sample);
    // The 2021 extension names its ground truth gt-nc-<sequence>.csv, same columns.
    fs::rename(root / "ground_truth" / "registered_poses.csv", root / "ground_truth" / "gt-nc-quad-easy.csv");
    auto reader = OpenDataset(root);
    EXPECT_EQ(reader->Info().poses_file.filename(), "gt-nc-quad-easy.csv");
    EXPECT_TRUE(reader->Info().has_reference_poses);
    std::ofstream(root / "ground_truth" / "gt-nc-quad-easy.csv", std::ios::app) << "1583836592,5,1.0,2.0\n";
    EXPECT_NE(test::DatasetErrorOf([&] { OpenDataset(root); }).find("gt-nc-quad-easy.csv:7: malformed sec,nsec"), std::string::npos);
    fs::remove(root / "ground_truth" / "gt-nc-quad-easy.csv");
    test::WriteBytes(root / "raw_format" / "ouster_scan" / "cloud_15838365.pcd", "x");
    EXPECT_NE(test::DatasetErrorOf([&] { OpenDataset(root); }).find("cloud_15838365.pcd: the scans of this layout are named cloud_<sec>_<nsec>"),
              std::string::npos);
}

TEST(NcltLayout, ScaledPointsTurnedZUpAndGroundTruthPairedByTime) {
    REVISIT_REQUIRE_DATA(test::SharedData("kitti00_first16"));
    const auto sample = test::LoadKittiSample(5);
    test::TempDir dir;
    test::MakeNclt(dir.path(), sample);
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
        EXPECT_NEAR(scan->timestamp - test::kNcltStart * 1e-6, sample.times[i], 1e-6) << i;
        ASSERT_TRUE(scan->T_world_sensor) << i;
        ExpectPosesNear(*scan->T_world_sensor, sample.poses[i], i);
    }
    EXPECT_FALSE(reader->Next());
    // The velodyne_sync folder itself names the same session.
    EXPECT_EQ(test::ReadAllScans(dir / "2012-01-08" / "velodyne_sync").size(), sample.scans.size());
    EXPECT_EQ(OpenDataset(dir / "2012-01-08" / "velodyne_sync")->Info().poses_file.filename(), "groundtruth_2012-01-08.csv");
}

TEST(NcltLayout, TruncatedScanAndBadGroundTruthLineAreNamed) {
    REVISIT_REQUIRE_DATA(test::SharedData("kitti00_first16"));
    const auto sample = test::LoadKittiSample(2);
    test::TempDir dir;
    test::MakeNclt(dir.path(), sample);
    const fs::path session = dir / "2012-01-08";
    const fs::path first = session / "velodyne_sync" / (test::Stamp(test::kNcltStart) + ".bin");
    const auto size = fs::file_size(first);
    fs::resize_file(first, size - 5);  // the last point cut short
    auto reader = OpenDataset(session);
    const std::string error = test::DatasetErrorOf([&] { reader->Next(); });
    EXPECT_NE(error.find(first.filename().string()), std::string::npos) << error;
    EXPECT_NE(error.find("byte offset " + std::to_string(size - 8)), std::string::npos) << error;
    std::ofstream(dir / "ground_truth" / "groundtruth_2012-01-08.csv", std::ios::app) << "1326030975926043,1.0,x,0,0,0,0\n";
    EXPECT_NE(test::DatasetErrorOf([&] { OpenDataset(session); }).find("groundtruth_2012-01-08.csv:5: malformed NCLT ground truth"),
              std::string::npos);
}

TEST(PublicLayoutsCli, InfoDescribesAndConvertWritesKittiAndRawlog) {
    REVISIT_REQUIRE_DATA(test::SharedData("kitti00_first16"));
    const auto sample = test::LoadKittiSample(3);
    test::TempDir dir;
    test::MakeNewerCollege(dir / "newer_college", sample);
    test::MakeNclt(dir / "nclt", sample);
    test::MakeHeLiPR(dir / "helipr", sample);
    const std::vector<std::pair<fs::path, std::string>> layouts = {{dir / "newer_college", "newer college"},
                                                                   {dir / "nclt" / "2012-01-08", "nclt"},
                                                                   {dir / "helipr", "helipr"}};
    for (const auto& [root, format] : layouts) {
        const auto info = test::RunCli("info " + test::Quote(root.string()));
        EXPECT_EQ(info.exit_code, 0) << info.output;
        EXPECT_NE(info.output.find("format:           " + format), std::string::npos) << info.output;
        EXPECT_NE(info.output.find("reference poses:  yes (3 scans)"), std::string::npos) << info.output;
        const auto original = test::ReadAllScans(root);
        for (const std::string out : {"kitti_out", "out.rawlog"}) {
            const fs::path target = dir / (format + "_" + out);
            const auto convert = test::RunCli("convert " + test::Quote(root.string()) + " " + test::Quote(target.string()));
            ASSERT_EQ(convert.exit_code, 0) << convert.output;
            const auto converted = test::ReadAllScans(target);
            ASSERT_EQ(converted.size(), original.size()) << target;
            for (std::size_t i = 0; i < original.size(); ++i) {
                EXPECT_EQ(converted[i].points, original[i].points) << target << " " << i;
                EXPECT_NEAR(converted[i].timestamp, original[i].timestamp, 1e-6) << target << " " << i;
                ASSERT_TRUE(converted[i].T_world_sensor) << target << " " << i;
                ExpectPosesNear(*converted[i].T_world_sensor, *original[i].T_world_sensor, i);
            }
        }
    }
}

}  // namespace
}  // namespace revisit
