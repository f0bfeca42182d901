/// The shared Livox walk recorded as ROS bags (../shared/data/bags, written by the official libraries)
/// reads back as the same scans as its KITTI folder: points bit-identical, stamps to the nanosecond,
/// reference poses = poses.txt, odometry prior = orig_odom_poses.txt.
#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <limits>

#include "read_all.hpp"
#include "core/error.hpp"
#include "io/bag_topics.hpp"
#include "io/reader.hpp"
#include "io/trajectory_io.hpp"
#include "test_data.hpp"

namespace revisit {
namespace {

const std::filesystem::path kBags = test::SharedData("bags");
const std::filesystem::path kWalk = test::SharedData("livox_handheld_walk");

/// orig_times.txt parsed exactly from its decimal text to nanoseconds.
std::vector<std::int64_t> StampsNs(const std::filesystem::path& file) {
    std::ifstream in(file);
    std::vector<std::int64_t> stamps;
    for (std::string line; std::getline(in, line);) {
        const auto dot = line.find('.');
        std::string fraction = dot == std::string::npos ? "" : line.substr(dot + 1);
        fraction.resize(9, '0');
        stamps.push_back(std::stoll(line.substr(0, dot)) * 1'000'000'000 + std::stoll(fraction));
    }
    return stamps;
}

const std::vector<Scan>& KittiScans() {
    static const std::vector<Scan> scans = test::ReadAllScans(kWalk);
    return scans;
}

/// The bag's poses carry the file's float64 position exactly and its rotation as a unit quaternion.
void ExpectPose(const Eigen::Isometry3d& actual, const Eigen::Isometry3d& expected, std::size_t i, const char* what) {
    EXPECT_EQ(actual.translation(), expected.translation()) << what << " scan " << i;
    EXPECT_LT((actual.linear() - expected.linear()).cwiseAbs().maxCoeff(), 1e-5) << what << " scan " << i;
}

class SharedBag : public testing::TestWithParam<const char*> {};

TEST_P(SharedBag, ReadsTheKittiFolderScansBitForBit) {
    const auto bag = kBags / GetParam();
    REVISIT_REQUIRE_DATA(bag);
    REVISIT_REQUIRE_DATA(kWalk);
    const auto& kitti = KittiScans();
    const auto stamps = StampsNs(kWalk / "orig_times.txt");
    const Trajectory reference = ReadKittiPoses(kWalk / "poses.txt");
    const Trajectory odometry = ReadKittiPoses(kWalk / "orig_odom_poses.txt");
    ASSERT_EQ(kitti.size(), 266u);
    ASSERT_EQ(stamps.size(), 266u);

    auto reader = OpenDataset(bag);
    EXPECT_EQ(reader->Info().num_scans, 266u);
    EXPECT_TRUE(reader->Info().has_reference_poses);
    EXPECT_TRUE(reader->Info().truncated.empty());
    std::size_t i = 0;
    while (auto scan = reader->Next()) {
        ASSERT_LT(i, kitti.size());
        const Scan& expected = kitti[i];
        EXPECT_EQ(scan->index, i);
        EXPECT_EQ(scan->sensor_label, "lidar");
        ASSERT_EQ(scan->points.size(), expected.points.size()) << "scan " << i;
        EXPECT_EQ(std::memcmp(scan->points.data(), expected.points.data(), expected.points.size() * sizeof(Eigen::Vector3f)), 0)
            << "scan " << i;
        ASSERT_EQ(scan->intensities.size(), expected.intensities.size());
        EXPECT_EQ(std::memcmp(scan->intensities.data(), expected.intensities.data(), expected.intensities.size() * 4), 0);
        EXPECT_TRUE(scan->point_times.empty());
        EXPECT_EQ(scan->stamp_ns, stamps[i]) << "scan " << i;
        EXPECT_EQ(scan->timestamp, double(stamps[i]) * 1e-9);
        ASSERT_TRUE(scan->T_world_sensor) << "scan " << i;
        ASSERT_TRUE(scan->T_odom_sensor) << "scan " << i;
        ExpectPose(*scan->T_world_sensor, reference.poses[i], i, "reference");
        ExpectPose(*scan->T_odom_sensor, odometry.poses[i], i, "odometry");
        ++i;
    }
    EXPECT_EQ(i, 266u);
    EXPECT_EQ(reader->Stats().non_finite_points, 0u);
    EXPECT_EQ(reader->Stats().points, 1'333'023u);
}

INSTANTIATE_TEST_SUITE_P(Formats, SharedBag,
                         testing::Values("livox_walk.mcap", "livox_walk_uncompressed.mcap", "livox_walk_db3",
                                         "livox_walk.bag", "livox_walk_bz2.bag"),
                         [](const auto& info) {
                             std::string name = info.param;
                             for (char& c : name) c = std::isalnum((unsigned char)c) ? c : '_';
                             return name;
                         });

TEST(RosBag, InfoListsEveryTopicWithItsRole) {
    const auto bag = kBags / "livox_walk.bag";
    REVISIT_REQUIRE_DATA(bag);
    auto reader = OpenDataset(bag);
    const auto& topics = reader->Info().topics;
    ASSERT_EQ(topics.size(), 4u);
    std::map<std::string, TopicSummary> by_name;
    for (const auto& t : topics) by_name[t.name] = t;
    EXPECT_EQ(by_name["/points"].role, "points");
    EXPECT_EQ(by_name["/points"].type, "sensor_msgs/PointCloud2");
    EXPECT_EQ(by_name["/points"].messages, 266u);
    EXPECT_NEAR(by_name["/points"].rate_hz, 265.0 / 102.599778, 1e-6);
    EXPECT_EQ(by_name["/odom"].role, "odometry");
    EXPECT_EQ(by_name["/ground_truth"].role, "reference");
    EXPECT_EQ(by_name["/tf_static"].role, "static transforms");
    EXPECT_EQ(by_name["/tf_static"].messages, 1u);
}

TEST(RosBag, RatesOfAnyStampsStayFiniteAndPositive) {
    // Stamps from a damaged file at the ends of int64 (found by fuzz_mcap): their difference overflows.
    BagTopic topic{"/points", "sensor_msgs/msg/PointCloud2", RosWire::kCdr, 3, std::numeric_limits<std::int64_t>::min() + 1, 2};
    const auto summary = SummarizeTopics({topic}, TopicChoice{});
    ASSERT_EQ(summary.size(), 1u);
    EXPECT_GT(summary[0].rate_hz, 0.0);
    EXPECT_LT(summary[0].rate_hz, 1e-9);  // 2 intervals over ~292 years
}

TEST(RosBag, NamedTopicsAndNone) {
    const auto bag = kBags / "livox_walk.mcap";
    REVISIT_REQUIRE_DATA(bag);
    ReaderOptions options;
    options.odometry_topic = "none";
    options.reference_topic = "/odom";  // an Odometry topic may be the reference when named
    auto reader = OpenDataset(bag, options);
    const auto scan = reader->Next();
    ASSERT_TRUE(scan);
    EXPECT_FALSE(scan->T_odom_sensor);
    ASSERT_TRUE(scan->T_world_sensor);
    options.points_topic = "/odom";
    try {
        OpenDataset(bag, options);
        FAIL() << "an Odometry topic is not a scan topic";
    } catch (const DatasetError& e) {
        EXPECT_NE(std::string(e.what()).find("/odom is a nav_msgs/Odometry topic"), std::string::npos) << e.what();
    }
    options.points_topic = "/nope";
    EXPECT_THROW(OpenDataset(bag, options), DatasetError);
}

}  // namespace
}  // namespace revisit
