#include <gtest/gtest.h>

#include <bzlib.h>
#include <zlib.h>

#include <cfloat>
#include <cmath>
#include <fstream>

#include "core/error.hpp"
#include "core/se3.hpp"
#include "io/carmen_reader.hpp"
#include "io/reader.hpp"
#include "test_data.hpp"

namespace revisit {
namespace {
namespace fs = std::filesystem;

std::vector<Scan> ReadAll(Reader& reader) {
    std::vector<Scan> scans;
    while (auto scan = reader.Next()) scans.push_back(std::move(*scan));
    return scans;
}

bool SameFloat(float a, float b) { return std::abs(a - b) <= 2.0f * FLT_EPSILON * std::max(1.0f, std::abs(b)); }

/// Each shared CARMEN log reads as the scans of its KITTI conversion (carmen_kitti/carmen_to_kitti.py):
/// the same points in the same order, the same poses, the same times.
class CarmenAgainstKitti : public ::testing::TestWithParam<const char*> {};

TEST_P(CarmenAgainstKitti, SameScansPosesAndTimes) {
    const std::string name = GetParam();
    const fs::path log = test::SharedData("carmen/" + name + "-corrected.log.gz");
    const fs::path kitti = test::SharedData("carmen_kitti/" + name);
    REVISIT_REQUIRE_DATA(log);
    REVISIT_REQUIRE_DATA(kitti);
    auto carmen_reader = OpenDataset(log);
    auto kitti_reader = OpenDataset(kitti);
    EXPECT_EQ(carmen_reader->Info().format, "carmen");
    ASSERT_TRUE(carmen_reader->Info().num_scans);
    EXPECT_EQ(*carmen_reader->Info().num_scans, *kitti_reader->Info().num_scans);
    const bool has_times = fs::exists(kitti / "times.txt");
    EXPECT_EQ(carmen_reader->Info().timing.empty(), has_times) << carmen_reader->Info().timing;
    const auto carmen = ReadAll(*carmen_reader);
    const auto converted = ReadAll(*kitti_reader);
    ASSERT_EQ(carmen.size(), converted.size());
    ASSERT_FALSE(carmen.empty());
    std::size_t points = 0;
    for (std::size_t k = 0; k < carmen.size(); ++k) {
        const Scan& a = carmen[k];
        const Scan& b = converted[k];
        ASSERT_EQ(a.points.size(), b.points.size()) << name << " scan " << k;
        for (std::size_t i = 0; i < a.points.size(); ++i) {
            ASSERT_TRUE(SameFloat(a.points[i].x(), b.points[i].x()) && SameFloat(a.points[i].y(), b.points[i].y()) &&
                        a.points[i].z() == 0.f)
                << name << " scan " << k << " point " << i << ": " << a.points[i].transpose() << " vs " << b.points[i].transpose();
        }
        points += a.points.size();
        ASSERT_TRUE(a.T_odom_sensor && b.T_world_sensor);
        EXPECT_LT((a.T_odom_sensor->matrix() - b.T_world_sensor->matrix()).norm(), 1e-6) << name << " scan " << k;
        EXPECT_FALSE(a.T_world_sensor);  // the laser poses are the odometry prior, not a reference
        ASSERT_TRUE(a.planar_beams);
        EXPECT_DOUBLE_EQ(a.planar_beams->aperture, M_PI);
        if (has_times) EXPECT_NEAR(a.timestamp - carmen[0].timestamp, b.timestamp, 1e-5) << name << " scan " << k;
        else EXPECT_NEAR(a.timestamp, 0.1 * static_cast<double>(k), 1e-12);
    }
    EXPECT_GT(points, carmen.size() * 50);
    EXPECT_EQ(carmen_reader->Stats().scans, carmen.size());
}

INSTANTIATE_TEST_SUITE_P(SharedLogs, CarmenAgainstKitti,
                         ::testing::Values("seattle", "freiburg-101", "belgioioso", "orebro"));

// A small log: PARAM, ODOM, two FLASER lines (5 beams; 10 m is the log's maximum reading), one
// RLASER line and a ROBOTLASER1 line with its own geometry and a laser 0.2 m ahead of the robot.
const char* kSmallLog =
    "# CARMEN logfile\n"
    "PARAM robot_front_laser_max 10.0 nohost 0\n"
    "ODOM 0 0 0 0 0 0 100.0 host 100.0\n"
    "FLASER 5 1.0 2.0 10.0 0.01 4.0 0.5 0.25 0.1 0.5 0.25 0.1 100.5 host 100.5\n"
    "RLASER 3 1 1 1 0 0 3.14 0 0 0 100.6 host 100.6\r\n"
    "FLASER 5 3.0 3.0 3.0 3.0 3.0 1.5 0.25 0.2 1.5 0.25 0.2 101.0 host 101.0\n";

void Write(const fs::path& file, const std::string& text) { std::ofstream(file, std::ios::binary) << text; }

TEST(CarmenReader, FlaserBeamsPosesAndNoReturns) {
    test::TempDir dir;
    Write(dir / "small.log", kSmallLog);
    auto reader = OpenDataset(dir / "small.log");
    const auto scans = ReadAll(*reader);
    ASSERT_EQ(scans.size(), 2u);
    EXPECT_EQ(reader->Stats().skipped_sensors.at("RLASER"), 1u);
    // Beams at -90, -45, 0, 45, 90 deg; 10.0 is the maximum reading (no return), 0.01 is below 5 cm.
    const Scan& s = scans[0];
    ASSERT_EQ(s.points.size(), 3u);
    EXPECT_NEAR(s.points[0].x(), 0.0, 1e-6);
    EXPECT_NEAR(s.points[0].y(), -1.0, 1e-6);
    EXPECT_NEAR(s.points[1].x(), 2.0 * std::cos(M_PI / 4), 1e-6);
    EXPECT_NEAR(s.points[1].y(), -2.0 * std::sin(M_PI / 4), 1e-6);
    EXPECT_NEAR(s.points[2].x(), 0.0, 1e-6);
    EXPECT_NEAR(s.points[2].y(), 4.0, 1e-6);
    ASSERT_TRUE(s.planar_beams);
    EXPECT_EQ(s.planar_beams->ranges, (std::vector<float>{1.f, 2.f, 0.f, 0.f, 4.f}));
    ASSERT_TRUE(s.T_odom_sensor);
    EXPECT_LT((s.T_odom_sensor->matrix() - PoseFromXYZRPY(0.5, 0.25, 0, 0, 0, 0.1).matrix()).norm(), 1e-12);
    EXPECT_DOUBLE_EQ(s.timestamp, 100.5);
    EXPECT_DOUBLE_EQ(scans[1].timestamp, 101.0);
    EXPECT_TRUE(reader->Info().timing.empty());
    // RLASER on request.
    ReaderOptions rear;
    rear.sensor_label = "RLASER";
    const auto rear_scans = ReadAll(*OpenDataset(dir / "small.log", rear));
    ASSERT_EQ(rear_scans.size(), 1u);
    EXPECT_EQ(rear_scans[0].sensor_label, "RLASER");
}

TEST(CarmenReader, RobotLaserUsesItsStatedGeometryAndLaserPose) {
    test::TempDir dir;
    // start -45 deg, fov 90 deg, 45 deg apart, max 5 m; 2 remissions; laser at (1.2, 0) of a robot at (1, 0).
    Write(dir / "robot.clf",
          "ROBOTLASER1 0 -0.785398163397 1.570796326795 0.785398163397 5.0 0.1 0 3 1.0 5.0 2.0 2 7 8 "
          "1.2 0 0 1 0 0 0 0 0 0 0 55.5 host 55.5\n");
    auto reader = OpenDataset(dir / "robot.clf");
    const auto scans = ReadAll(*reader);
    ASSERT_EQ(scans.size(), 1u);
    const Scan& s = scans[0];
    ASSERT_EQ(s.points.size(), 2u);  // 5.0 is the stated maximum range
    EXPECT_NEAR(s.points[0].x(), std::cos(M_PI / 4), 1e-6);
    EXPECT_NEAR(s.points[0].y(), -std::sin(M_PI / 4), 1e-6);
    EXPECT_NEAR(s.points[1].x(), 2.0 * std::cos(M_PI / 4), 1e-6);
    EXPECT_NEAR(s.points[1].y(), 2.0 * std::sin(M_PI / 4), 1e-6);
    EXPECT_NEAR(s.planar_beams->stated_aperture, M_PI / 2, 1e-9);
    EXPECT_NEAR(s.planar_beams->T_vehicle_sensor.translation().x(), 0.2, 1e-12);
    EXPECT_NEAR(s.T_odom_sensor->translation().x(), 1.2, 1e-12);
    EXPECT_DOUBLE_EQ(s.timestamp, 55.5);
}

std::string Gzip(const std::string& text) {
    std::string out(compressBound(text.size()) + 64, '\0');
    z_stream z{};
    deflateInit2(&z, Z_DEFAULT_COMPRESSION, Z_DEFLATED, 16 + MAX_WBITS, 8, Z_DEFAULT_STRATEGY);
    z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(text.data()));
    z.avail_in = static_cast<uInt>(text.size());
    z.next_out = reinterpret_cast<Bytef*>(out.data());
    z.avail_out = static_cast<uInt>(out.size());
    deflate(&z, Z_FINISH);
    out.resize(z.total_out);
    deflateEnd(&z);
    return out;
}

std::string Bzip2(const std::string& text) {
    std::string out(text.size() + text.size() / 100 + 1024, '\0');
    unsigned length = static_cast<unsigned>(out.size());
    BZ2_bzBuffToBuffCompress(out.data(), &length, const_cast<char*>(text.data()), static_cast<unsigned>(text.size()), 9, 0, 0);
    out.resize(length);
    return out;
}

TEST(CarmenReader, GzipAndBzip2ReadTheSameAndDamageIsNamed) {
    test::TempDir dir;
    Write(dir / "a.log", kSmallLog);
    Write(dir / "a.log.gz", Gzip(kSmallLog));
    Write(dir / "a.log.bz2", Bzip2(kSmallLog));
    const auto plain = ReadAll(*OpenDataset(dir / "a.log"));
    for (const char* name : {"a.log.gz", "a.log.bz2"}) {
        const auto scans = ReadAll(*OpenDataset(dir / name));
        ASSERT_EQ(scans.size(), plain.size()) << name;
        for (std::size_t k = 0; k < scans.size(); ++k) EXPECT_EQ(scans[k].points, plain[k].points) << name;
    }
    const std::string bz = Bzip2(kSmallLog);
    Write(dir / "cut.log.bz2", bz.substr(0, bz.size() / 2));
    try {
        ReadAll(*OpenDataset(dir / "cut.log.bz2"));
        FAIL() << "a truncated bzip2 log was read";
    } catch (const DatasetError& e) {
        EXPECT_NE(std::string(e.what()).find("bzip2"), std::string::npos) << e.what();
    }
}

TEST(CarmenReader, BadLinesAndOtherFilesAreNamedErrors) {
    test::TempDir dir;
    const auto expect_error = [&](const std::string& text, const std::string& expected) {
        Write(dir / "bad.log", text);
        try {
            OpenDataset(dir / "bad.log");
            ADD_FAILURE() << "accepted: " << text;
        } catch (const DatasetError& e) {
            EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
        }
    };
    expect_error("2024-01-01 12:00 server started\n", "not a CARMEN log");
    expect_error("PARAM a b nohost 0\nFLASER 3 1.0 2.0\n", "bad.log:2: FLASER line: the number of readings 3 is not a count");
    expect_error("PARAM a b nohost 0\nFLASER 2 1.0 2.0 0 0\n", "bad.log:2: FLASER line: ends before the laser pose");
    expect_error("FLASER 1000000000 1 2 3\n", "bad.log:1: FLASER line: the number of readings");
    expect_error("ODOM 0 0 0 0 0 0 1 h 1\nFLASER 2 1 nan 0 0 0 0 0 0 1 h 1\n", "bad.log:2: FLASER line: a range");
    expect_error("PARAM a b nohost 0\nODOM 0 0 0 0 0 0 1 h 1\n", "no laser lines");
    expect_error("", "empty");
}

TEST(CarmenReader, ZeroTimesGetANominalPeriod) {
    test::TempDir dir;
    Write(dir / "z.log", "FLASER 2 1 1 0 0 0 0 0 0 0 h 0\nFLASER 2 1 1 0 0 0 0 0 0 0 h 0\nFLASER 2 1 1 0 0 0 0 0 0 0 h 0\n");
    auto reader = OpenDataset(dir / "z.log");
    const auto scans = ReadAll(*reader);
    ASSERT_EQ(scans.size(), 3u);
    EXPECT_DOUBLE_EQ(scans[2].timestamp, 0.2);
    EXPECT_NE(reader->Info().timing.find("nominal"), std::string::npos);
}

}  // namespace
}  // namespace revisit
