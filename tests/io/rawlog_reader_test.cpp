#include <gtest/gtest.h>

#include <fstream>

#include "read_all.hpp"
#include "core/error.hpp"
#include "core/trajectory.hpp"
#include "io/dataset_summary.hpp"
#include "io/reader.hpp"
#include "io/writer.hpp"
#include "test_data.hpp"

namespace revisit {
namespace {

TEST(RawlogReader, SenaLoopActionSensoryFrameLayout) {
    const auto file = test::MrptDataset("2006-01ENE-21-SENA_Telecom Faculty_one_loop_only.rawlog");
    REVISIT_REQUIRE_DATA(file);
    auto reader = OpenDataset(file);
    const auto summary = Summarize(*reader);
    EXPECT_EQ(summary.num_scans, 225u);  // as MRPT's CRawlog::loadFromRawLogFile (the pair reader lost the last one)
    EXPECT_EQ(summary.scans_with_odometry, 224u);  // the first scan comes before any odometry
    EXPECT_GT(summary.points_min, 200u);
    EXPECT_LE(summary.points_max, 361u);
    EXPECT_NEAR(summary.trajectory_length, 76.3, 1.0);
    ASSERT_TRUE(summary.closest_return);
    EXPECT_LT(summary.closest_return->distance, 1.0);  // one loop: the robot comes back
}

TEST(RawlogReader, RotatingScanMatchesTheSameVelodyneScan) {
    // MRPT ships the same VLP-16 sweep twice: raw packets and as a range image. Our range-image
    // conversion (datasheet elevations) must reproduce MRPT's own point cloud.
    const auto velodyne_file = test::MrptDataset("test_velodyne_VLP16.rawlog");
    const auto rotating_file = test::MrptDataset("rot_scan_velodyne.rawlog");
    REVISIT_REQUIRE_DATA(velodyne_file);
    REVISIT_REQUIRE_DATA(rotating_file);
    const auto velodyne = test::ReadAllScans(velodyne_file);
    const auto rotating = test::ReadAllScans(rotating_file);
    ASSERT_EQ(velodyne.size(), 1u);
    ASSERT_EQ(rotating.size(), 1u);
    EXPECT_EQ(velodyne[0].sensor_label, "Velodyne1_SCAN");
    EXPECT_EQ(rotating[0].points.size(), velodyne[0].points.size());
    // Compare the clouds by their spread and centroid (point order differs between the classes).
    const auto centroid = [](const std::vector<Eigen::Vector3f>& pts) {
        Eigen::Vector3d c = Eigen::Vector3d::Zero();
        for (const auto& p : pts) c += p.cast<double>();
        return Eigen::Vector3d(c / static_cast<double>(pts.size()));
    };
    EXPECT_LT((centroid(rotating[0].points) - centroid(velodyne[0].points)).norm(), 0.1);
    EXPECT_EQ(rotating[0].point_times.size(), rotating[0].points.size());
}

TEST(RawlogReader, DepthCameraScanIsUnprojected) {
    const auto file = test::MrptDataset("tests_rgbd.rawlog");
    REVISIT_REQUIRE_DATA(file);
    const auto scans = test::ReadAllScans(file);
    ASSERT_EQ(scans.size(), 1u);
    EXPECT_GT(scans[0].points.size(), 100000u);
    // A depth camera sees in front of it: MRPT's sensor frame has +x forward.
    std::size_t in_front = 0;
    for (const auto& p : scans[0].points) in_front += p.x() > 0.f;
    EXPECT_GT(in_front, scans[0].points.size() * 9 / 10);
}

TEST(RawlogReader, UnknownClassesAreSkippedAndCounted) {
    const auto file = test::MrptDataset("kf-slam_6D_demo.rawlog");
    REVISIT_REQUIRE_DATA(file);
    auto reader = OpenDataset(file);
    EXPECT_FALSE(reader->Next());
    EXPECT_EQ(reader->Stats().skipped_classes.at("mrpt::obs::CObservationBearingRange"), 600u);
    EXPECT_NE(DescribeDrops(reader->Stats()).find("CObservationBearingRange x600"), std::string::npos);
}

TEST(RawlogReader, SensorLabelFilter) {
    const auto file = test::MrptDataset("test_velodyne_VLP16.rawlog");
    REVISIT_REQUIRE_DATA(file);
    ReaderOptions options;
    options.sensor_label = "SOMETHING_ELSE";
    auto reader = OpenDataset(file, options);
    EXPECT_FALSE(reader->Next());
    EXPECT_EQ(reader->Stats().skipped_sensors.at("Velodyne1_SCAN"), 1u);
}

TEST(RawlogReader, RealRadishLogs) {
    struct Log { const char* name; std::size_t scans; double path_m; };
    for (const Log log : {Log{"radish/fr079.rawlog", 4934, 392.0}, Log{"radish/intel.rawlog", 13631, 508.0}}) {
        const auto file = test::SharedData(log.name);
        REVISIT_REQUIRE_DATA(file);
        auto reader = OpenDataset(file);
        const auto summary = Summarize(*reader);
        EXPECT_EQ(summary.num_scans, log.scans) << log.name;
        EXPECT_EQ(summary.scans_with_odometry, log.scans) << log.name;
        EXPECT_NEAR(summary.trajectory_length, log.path_m, 0.02 * log.path_m) << log.name;
        ASSERT_TRUE(summary.closest_return) << log.name;
        EXPECT_LT(summary.closest_return->distance, 0.5) << log.name;
    }
}

TEST(RawlogReader, CorruptGzipIsAnErrorNotACrash) {
    const auto file = test::SharedData("radish/fr079.rawlog");
    REVISIT_REQUIRE_DATA(file);
    test::TempDir dir;
    {
        std::ifstream in(file, std::ios::binary);
        std::vector<char> bytes(200000);
        in.read(bytes.data(), static_cast<std::streamsize>(bytes.size()));
        for (std::size_t i = 100000; i < 100400; ++i) bytes[i] = static_cast<char>(i * 31);  // garble the stream
        std::ofstream(dir / "bad.rawlog", std::ios::binary).write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    }
    auto reader = OpenDataset(dir / "bad.rawlog");
    std::size_t scans = 0;
    try {
        while (reader->Next()) ++scans;
    } catch (const DatasetError& e) {
        EXPECT_NE(std::string(e.what()).find("bad.rawlog"), std::string::npos);
    }
    EXPECT_GT(scans, 10u);  // what came before the damage is still read
    EXPECT_LT(scans, 4934u);
}

TEST(RawlogWriter, PlanarRangeScansRoundTrip) {
    test::TempDir dir;
    WriterOptions options;
    options.planar_as_range_scan = true;
    options.planar_beams = 181;
    options.planar_aperture = M_PI;
    {
        auto writer = CreateRawlogWriter(dir / "laser.rawlog", options);
        for (int s = 0; s < 3; ++s) {
            Scan scan;
            scan.timestamp = 5.0 + s;
            for (int beam = 0; beam < 181; beam += 2) {
                const double angle = -M_PI / 2 + beam * M_PI / 180.0;
                scan.points.emplace_back(static_cast<float>(4.0 * std::cos(angle)), static_cast<float>(4.0 * std::sin(angle)), 0.f);
            }
            scan.T_odom_sensor = Eigen::Isometry3d(Eigen::Translation3d(s * 0.5, 0.0, 0.0));
            writer->Write(scan);
        }
        writer->Finish();
    }
    const auto scans = test::ReadAllScans(dir / "laser.rawlog");
    ASSERT_EQ(scans.size(), 3u);
    EXPECT_EQ(scans[1].points.size(), 91u);
    EXPECT_NEAR(scans[1].points[10].norm(), 4.0, 1e-4);
    ASSERT_TRUE(scans[2].T_odom_sensor);
    EXPECT_NEAR(scans[2].T_odom_sensor->translation().x(), 1.0, 1e-9);
    EXPECT_NEAR(scans[2].timestamp, 7.0, 1e-6);
}

}  // namespace
}  // namespace revisit

namespace revisit {
namespace {
TEST(RawlogReader, LaserApertureOverrideSpreadsTheBeams) {
    const auto file = test::SharedData("radish/intel.rawlog");
    REVISIT_REQUIRE_DATA(file);
    const auto angular_span = [&](double aperture) {
        ReaderOptions options;
        options.laser_aperture = aperture;
        auto scan = OpenDataset(file, options)->Next();
        double lo = 10, hi = -10;
        for (const auto& p : scan->points) {
            lo = std::min(lo, std::atan2(static_cast<double>(p.y()), static_cast<double>(p.x())));
            hi = std::max(hi, std::atan2(static_cast<double>(p.y()), static_cast<double>(p.x())));
        }
        return hi - lo;
    };
    EXPECT_LE(angular_span(0.0), M_PI / 2 + 1e-3);  // the file's (wrong) 90 degrees
    EXPECT_GT(angular_span(M_PI), 0.9 * M_PI);      // the SICK's real 180 degrees
}
}  // namespace
}  // namespace revisit

namespace revisit {
namespace {
namespace fs = std::filesystem;

/// A plain rawlog of scans at `times` [s], 40 points each.
void WriteTimedRawlog(const fs::path& file, const std::vector<double>& times) {
    auto writer = CreateRawlogWriter(file);
    for (std::size_t s = 0; s < times.size(); ++s) {
        Scan scan;
        scan.timestamp = times[s];
        for (int i = 0; i < 40; ++i) scan.points.emplace_back(i * 0.25f, static_cast<float>(s), 0.5f);
        writer->Write(scan);
    }
    writer->Finish();
}

std::string ReadError(const fs::path& file, const ReaderOptions& options = {}) {
    try {
        test::ReadAllScans(file, options);
    } catch (const DatasetError& e) {
        return e.what();
    }
    return "";
}

TEST(RawlogReader, TimeGoingBackwardsIsANamedErrorWithItsObjectWhileReading) {
    test::TempDir dir;
    // Two recordings concatenated: 5, 6, 7 then 2, 3.
    WriteTimedRawlog(dir / "twice.rawlog", {5.0, 6.0, 7.0, 2.0, 3.0});
    const std::string error = ReadError(dir / "twice.rawlog");
    EXPECT_NE(error.find((dir / "twice.rawlog").string()), std::string::npos) << error;
    EXPECT_NE(error.find("time goes backwards in object 3 (starts at byte "), std::string::npos) << error;
    EXPECT_NE(error.find("scan 3 at 2 s after 7 s"), std::string::npos) << error;
    // --allow-truncated keeps the scans before it, and says why reading stopped.
    ReaderOptions allow;
    allow.allow_truncated = true;
    auto reader = OpenDataset(dir / "twice.rawlog", allow);
    std::size_t scans = 0;
    while (reader->Next()) ++scans;
    EXPECT_EQ(scans, 3u);
    EXPECT_NE(reader->Info().truncated.find("time goes backwards"), std::string::npos);
    // Equal times (a sensor without a clock writes 0) are not a step backwards.
    WriteTimedRawlog(dir / "zero.rawlog", {0.0, 0.0, 0.0});
    EXPECT_EQ(test::ReadAllScans(dir / "zero.rawlog").size(), 3u);
}

TEST(RawlogReader, DamageIsNamedAtTheObjectsOwnOffset) {
    test::TempDir dir;
    WriteTimedRawlog(dir / "two.rawlog", {1.0, 2.0});
    WriteTimedRawlog(dir / "three.rawlog", {1.0, 2.0, 3.0});
    const std::string two = test::ReadFile(dir / "two.rawlog");
    std::string bytes = test::ReadFile(dir / "three.rawlog");
    ASSERT_EQ(bytes.compare(0, two.size(), two), 0);  // object 2 starts where the first two end
    // A flipped bit in object 2's class name ("mrpt::obs::CObs..." -> "...COBs...": no such class).
    ASSERT_EQ(bytes.substr(two.size() + 1, 15), "mrpt::obs::CObs");
    bytes[two.size() + 14] ^= 0x20;
    std::ofstream(dir / "flipped.rawlog", std::ios::binary) << bytes;
    const std::string error = ReadError(dir / "flipped.rawlog");
    EXPECT_NE(error.find("reading stopped in object 2 (starts at byte " + std::to_string(two.size()) + " of " +
                         std::to_string(bytes.size()) + ")"),
              std::string::npos)
        << error;
}

}  // namespace
}  // namespace revisit
