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

/// The published Aeva files gained an intensity field after this stamp: the fixture's clock starts
/// 0.25 s before it, so its first three scans have the older 25-byte layout and the rest 29 bytes.
constexpr std::uint64_t kAevaIntensitySince = 1691936557946849179ull;
constexpr std::uint64_t kStart = kAevaIntensitySince - 250000000ull;  ///< [ns]

std::uint64_t StampOf(double t) { return kStart + static_cast<std::uint64_t>(std::llround(t * 1e9)); }
float PointTime(std::size_t p) { return static_cast<float>(p % 1000) * 1e-4f; }  ///< [s] within the sweep

/// One scan in a sensor's published record layout (float32 x, y, z first in all of them).
std::string Encode(const std::string& sensor, const Scan& scan, bool aeva_intensity) {
    std::string bin;
    for (std::size_t p = 0; p < scan.points.size(); ++p) {
        for (int c = 0; c < 3; ++c) test::AppendRaw(bin, scan.points[p][c]);
        const float intensity = scan.intensities[p];
        const auto ns = static_cast<std::uint32_t>(std::lround(PointTime(p) * 1e9));
        if (sensor == "Ouster") {
            test::AppendRaw(bin, intensity);
            test::AppendRaw(bin, ns);
            for (std::uint16_t v : {std::uint16_t(7), std::uint16_t(p % 128), std::uint16_t(300)}) test::AppendRaw(bin, v);
        } else if (sensor == "Velodyne") {
            test::AppendRaw(bin, intensity);
            test::AppendRaw(bin, static_cast<std::uint16_t>(p % 16));
            test::AppendRaw(bin, PointTime(p));
        } else if (sensor == "Avia") {
            test::AppendRaw(bin, static_cast<std::uint8_t>(std::lround(intensity * 255.f)));
            test::AppendRaw(bin, std::uint8_t(0));
            test::AppendRaw(bin, static_cast<std::uint8_t>(p % 6));
            test::AppendRaw(bin, ns);
        } else {  // Aeva: reflectivity, velocity, time_offset_ns, line_index [, intensity]
            test::AppendRaw(bin, aeva_intensity ? 0.5f : intensity);
            test::AppendRaw(bin, -1.25f);
            test::AppendRaw(bin, static_cast<std::int32_t>(ns));
            test::AppendRaw(bin, static_cast<std::uint8_t>(p % 64));
            if (aeva_intensity) test::AppendRaw(bin, intensity);
        }
    }
    return bin;
}

/// HeLiPR: LiDAR/<sensor>/<ns>.bin for the four sensors and LiDAR_GT/<sensor>_gt.txt (ns x y z qx qy qz
/// qw, space-separated) at twice the scan rate in UTM-like coordinates.
void MakeHeLiPR(const fs::path& root, const test::KittiSample& sample) {
    for (const std::string sensor : {"Ouster", "Velodyne", "Avia", "Aeva"}) {
        for (std::size_t i = 0; i < sample.scans.size(); ++i) {
            const std::uint64_t stamp = StampOf(sample.times[i]);
            test::WriteBytes(root / "LiDAR" / sensor / (std::to_string(stamp) + ".bin"),
                             Encode(sensor, sample.scans[i], stamp > kAevaIntensitySince));
        }
        fs::create_directories(root / "LiDAR_GT");
        std::ofstream gt(root / "LiDAR_GT" / (sensor + "_gt.txt"));
        for (const auto& [t, T] : test::TwiceRatePoses(sample)) {
            const Eigen::Quaterniond q(T.linear());
            char line[256];
            std::snprintf(line, sizeof line, "%llu %.9f %.9f %.9f %.12f %.12f %.12f %.12f\n",
                          static_cast<unsigned long long>(StampOf(t)), T.translation().x() + 325000.0,
                          T.translation().y() + 4150000.0, T.translation().z() + 30.0, q.x(), q.y(), q.z(), q.w());
            gt << line;
        }
    }
}

std::string ErrorOf(const std::function<void()>& action) {
    try {
        action();
    } catch (const DatasetError& e) {
        return e.what();
    }
    return "(no error)";
}

TEST(HeLiPRLayout, EachSensorsRecordsAndGroundTruthPairedByTime) {
    REVISIT_REQUIRE_DATA(test::SharedData("kitti00_first16"));
    const auto sample = test::LoadKittiSample(5);
    test::TempDir dir;
    MakeHeLiPR(dir / "Roundabout01", sample);
    for (const std::string sensor : {"", "Ouster", "velodyne", "Avia", "Aeva"}) {
        ReaderOptions options;
        options.sensor_label = sensor;
        auto reader = OpenDataset(dir / "Roundabout01", options);
        EXPECT_EQ(reader->Info().format, "helipr");
        const std::string name = sensor.empty() ? "Ouster" : sensor == "velodyne" ? "Velodyne" : sensor;
        EXPECT_EQ(reader->Info().poses_file.filename(), name + "_gt.txt");
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
                EXPECT_NEAR(scan->point_times[p], PointTime(p), 1e-7) << name << " " << i << " " << p;
            }
            EXPECT_NEAR(scan->timestamp - kStart * 1e-9, sample.times[i], 1e-6) << name << " " << i;
            ASSERT_TRUE(scan->T_world_sensor) << name << " " << i;
            // The UTM-like positions, moved so that the first is at the origin.
            const Eigen::Vector3d position = sample.poses[i].translation() - sample.poses[0].translation();
            EXPECT_LT((scan->T_world_sensor->translation() - position).norm(), 1e-5) << name << " " << i;
            EXPECT_LT((scan->T_world_sensor->linear() - sample.poses[i].linear()).norm(), 1e-6) << name << " " << i;
        }
        EXPECT_FALSE(reader->Next()) << name;
    }
}

TEST(HeLiPRLayout, BadRecordSizesSensorsAndGroundTruthLinesAreNamed) {
    REVISIT_REQUIRE_DATA(test::SharedData("kitti00_first16"));
    const auto sample = test::LoadKittiSample(2);
    test::TempDir dir;
    const fs::path root = dir / "DCC04";
    MakeHeLiPR(root, sample);
    // An Ouster file one byte short of whole 26-byte records.
    const fs::path ouster = root / "LiDAR" / "Ouster" / (std::to_string(StampOf(sample.times[0])) + ".bin");
    const auto size = fs::file_size(ouster);
    fs::resize_file(ouster, size - 1);
    std::string error = ErrorOf([&] { LoadHeLiPRBin(ouster, "Ouster"); });
    EXPECT_NE(error.find(ouster.string() + ": size " + std::to_string(size - 1) + " bytes is not a multiple of 26"), std::string::npos)
        << error;
    EXPECT_NE(error.find("byte offset " + std::to_string(size - 26)), std::string::npos) << error;
    // An early Aeva file (25-byte records) read as the later layout would not be a whole number of 29s.
    const fs::path aeva = root / "LiDAR" / "Aeva" / (std::to_string(StampOf(sample.times[0])) + ".bin");
    EXPECT_EQ(LoadHeLiPRBin(aeva, "Aeva").points.size(), sample.scans[0].points.size());
    fs::rename(aeva, root / "LiDAR" / "Aeva" / (std::to_string(kAevaIntensitySince + 1) + ".bin"));
    error = ErrorOf([&] { LoadHeLiPRBin(root / "LiDAR" / "Aeva" / (std::to_string(kAevaIntensitySince + 1) + ".bin"), "Aeva"); });
    EXPECT_NE(error.find("is not a multiple of 29"), std::string::npos) << error;
    ReaderOptions options;
    options.sensor_label = "Hesai";
    error = ErrorOf([&] { OpenDataset(root, options); });
    EXPECT_NE(error.find("the sensors here: Ouster, Velodyne, Avia, Aeva"), std::string::npos) << error;
    std::ofstream(root / "LiDAR_GT" / "Velodyne_gt.txt", std::ios::app) << "1691936558000000000 1 2 3 0 0 0\n";
    options.sensor_label = "Velodyne";
    error = ErrorOf([&] { OpenDataset(root, options); });
    EXPECT_NE(error.find("Velodyne_gt.txt:4: malformed HeLiPR ground truth"), std::string::npos) << error;
}

}  // namespace
}  // namespace revisit
