#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>

#include "core/error.hpp"
#include "io/helipr.hpp"
#include "io/reader.hpp"
#include "layout_fixtures.hpp"

namespace revisit {
namespace {
namespace fs = std::filesystem;

TEST(HeLiPRLayout, EachSensorsRecordsAndGroundTruthPairedByTime) {
    REVISIT_REQUIRE_DATA(test::SharedData("kitti00_first16"));
    const auto sample = test::LoadKittiSample(5);
    test::TempDir dir;
    test::MakeHeLiPR(dir / "Roundabout01", sample);
    for (const std::string sensor : {"", "Ouster", "velodyne", "Avia", "Aeva"}) {
        ReaderOptions options;
        options.sensor_label = sensor;
        auto reader = OpenDataset(dir / "Roundabout01", options);
        EXPECT_EQ(reader->Info().format, "helipr");
        const std::string name = sensor.empty() ? "Ouster" : sensor == "velodyne" ? "Velodyne" : sensor;
        EXPECT_EQ(reader->Info().poses_file.filename(), name + "_gt.txt");
        // `revisit info` lists the four sensor folders, the one read and how to read the others.
        const auto& folders = reader->Info().topics;
        ASSERT_EQ(folders.size(), 4u) << name;
        for (const auto& folder : folders) {
            EXPECT_EQ(folder.messages, sample.scans.size()) << folder.name;
            EXPECT_NEAR(folder.rate_hz, (sample.scans.size() - 1) / (sample.times.back() - sample.times.front()), 1e-3) << folder.name;
            EXPECT_EQ(folder.role, folder.name == "LiDAR/" + name ? "points" : "unused (--sensor " + folder.name.substr(6) + ")");
        }
        for (std::size_t i = 0; i < sample.scans.size(); ++i) {
            const auto scan = reader->Next();
            ASSERT_TRUE(scan) << name << " " << i;
            const Scan& expected = sample.scans[i];
            EXPECT_EQ(scan->points, expected.points) << name << " " << i;
            ASSERT_EQ(scan->intensities.size(), expected.points.size()) << name << " " << i;
            ASSERT_EQ(scan->point_times.size(), expected.points.size()) << name << " " << i;
            for (std::size_t p = 0; p < expected.points.size(); p += 97) {
                const float intensity = name == "Avia" ? std::round(expected.intensities[p] * 255.f) : expected.intensities[p];
                EXPECT_EQ(scan->intensities[p], intensity) << name << " " << i << " " << p;
                EXPECT_NEAR(scan->point_times[p], test::PointTime(p), 1e-7) << name << " " << i << " " << p;
            }
            EXPECT_NEAR(scan->timestamp - test::kHeLiPRStart * 1e-9, sample.times[i], 1e-6) << name << " " << i;
            ASSERT_TRUE(scan->T_world_sensor) << name << " " << i;
            // The UTM-like positions, moved so that the first is at the origin.
            const Eigen::Vector3d position = sample.poses[i].translation() - sample.poses[0].translation();
            EXPECT_LT((scan->T_world_sensor->translation() - position).norm(), 1e-5) << name << " " << i;
            EXPECT_LT((scan->T_world_sensor->linear() - sample.poses[i].linear()).norm(), 1e-6) << name << " " << i;
        }
        EXPECT_FALSE(reader->Next()) << name;
    }
    // A sensor's own folder names the sequence and that sensor.
    const fs::path velodyne = dir / "Roundabout01" / "LiDAR" / "Velodyne";
    auto reader = OpenDataset(velodyne);
    EXPECT_EQ(reader->Info().poses_file.filename(), "Velodyne_gt.txt");
    EXPECT_EQ(reader->Next()->sensor_label, "VELODYNE");
    ReaderOptions avia;
    avia.sensor_label = "Avia";
    EXPECT_NE(test::DatasetErrorOf([&] { OpenDataset(velodyne, avia); }).find("this is the Velodyne folder, but --sensor asks for Avia"),
              std::string::npos);
}

TEST(HeLiPRLayout, BadRecordSizesSensorsAndGroundTruthLinesAreNamed) {
    REVISIT_REQUIRE_DATA(test::SharedData("kitti00_first16"));
    const auto sample = test::LoadKittiSample(2);
    test::TempDir dir;
    const fs::path root = dir / "DCC04";
    test::MakeHeLiPR(root, sample);
    // An Ouster file one byte short of whole 26-byte records.
    const fs::path ouster = root / "LiDAR" / "Ouster" / (std::to_string(test::HeLiPRStamp(sample.times[0])) + ".bin");
    const auto size = fs::file_size(ouster);
    fs::resize_file(ouster, size - 1);
    std::string error = test::DatasetErrorOf([&] { LoadHeLiPRBin(ouster, "Ouster"); });
    EXPECT_NE(error.find(ouster.string() + ": size " + std::to_string(size - 1) + " bytes is not a multiple of 26"), std::string::npos)
        << error;
    EXPECT_NE(error.find("byte offset " + std::to_string(size - 26)), std::string::npos) << error;
    // An early Aeva file (25-byte records) read as the later layout would not be a whole number of 29s.
    const fs::path aeva = root / "LiDAR" / "Aeva" / (std::to_string(test::HeLiPRStamp(sample.times[0])) + ".bin");
    EXPECT_EQ(LoadHeLiPRBin(aeva, "Aeva").points.size(), sample.scans[0].points.size());
    fs::rename(aeva, root / "LiDAR" / "Aeva" / (std::to_string(test::kAevaIntensitySince + 1) + ".bin"));
    error = test::DatasetErrorOf([&] { LoadHeLiPRBin(root / "LiDAR" / "Aeva" / (std::to_string(test::kAevaIntensitySince + 1) + ".bin"), "Aeva"); });
    EXPECT_NE(error.find("is not a multiple of 29"), std::string::npos) << error;
    ReaderOptions options;
    options.sensor_label = "Hesai";
    error = test::DatasetErrorOf([&] { OpenDataset(root, options); });
    EXPECT_NE(error.find("the sensors here: Ouster, Velodyne, Avia, Aeva"), std::string::npos) << error;
    std::ofstream(root / "LiDAR_GT" / "Velodyne_gt.txt", std::ios::app) << "1691936558000000000 1 2 3 0 0 0\n";
    options.sensor_label = "Velodyne";
    error = test::DatasetErrorOf([&] { OpenDataset(root, options); });
    EXPECT_NE(error.find("Velodyne_gt.txt:4: malformed HeLiPR ground truth"), std::string::npos) << error;
}

}  // namespace
}  // namespace revisit
