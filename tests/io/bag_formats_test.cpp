/// rosbag2 sqlite3 layouts beyond Humble's (Iron's schema version 4) and ROS 1 bags with lz4 chunks,
/// both written here: the shared recordings have neither.
#include <gtest/gtest.h>
#include <sqlite3.h>

#include <fstream>

#include "read_all.hpp"
#include "core/error.hpp"
#include "io/reader.hpp"
#include "mcap_test_writer.hpp"
#include "test_data.hpp"

#ifdef REVISIT_HAVE_ROSBAG
#include <rosbag/bag.h>

#include "ros1_cloud.hpp"
#endif

namespace revisit {
namespace {

void Exec(sqlite3* db, const std::string& sql) {
    char* error = nullptr;
    ASSERT_EQ(sqlite3_exec(db, sql.c_str(), nullptr, nullptr, &error), SQLITE_OK) << (error ? error : "");
}

TEST(Rosbag2Sqlite, IronSchemaVersion4OrderedByTimestampThenId) {
    test::TempDir dir;
    const auto folder = dir / "bag";
    std::filesystem::create_directories(folder);
    std::ofstream(folder / "metadata.yaml") << "rosbag2_bagfile_information:\n  version: 8\n  storage_identifier: sqlite3\n"
                                               "  relative_file_paths:\n    - bag_0.db3\n  compression_format: \"\"\n";
    sqlite3* db = nullptr;
    ASSERT_EQ(sqlite3_open((folder / "bag_0.db3").c_str(), &db), SQLITE_OK);
    Exec(db, "CREATE TABLE schema(schema_version INTEGER PRIMARY KEY, ros_distro TEXT NOT NULL);"
             "INSERT INTO schema VALUES (4, 'iron');"
             "CREATE TABLE metadata(id INTEGER PRIMARY KEY, metadata_version INTEGER NOT NULL, metadata TEXT NOT NULL);"
             "CREATE TABLE topics(id INTEGER PRIMARY KEY, name TEXT NOT NULL, type TEXT NOT NULL, serialization_format TEXT NOT NULL,"
             " offered_qos_profiles TEXT NOT NULL, type_description_hash TEXT NOT NULL);"
             "CREATE TABLE message_definitions(id INTEGER PRIMARY KEY, topic_type TEXT NOT NULL, encoding TEXT NOT NULL,"
             " encoded_message_definition TEXT NOT NULL, type_description_hash TEXT NOT NULL);"
             "CREATE TABLE messages(id INTEGER PRIMARY KEY, topic_id INTEGER NOT NULL, timestamp INTEGER NOT NULL, data BLOB NOT NULL);"
             "INSERT INTO topics VALUES (7, '/cloud', 'sensor_msgs/msg/PointCloud2', 'cdr', '- history: 1', 'RIHS01_00');"
             "INSERT INTO message_definitions VALUES (1, 'sensor_msgs/msg/PointCloud2', 'ros2msg', '', 'RIHS01_00');");
    sqlite3_stmt* insert = nullptr;
    ASSERT_EQ(sqlite3_prepare_v2(db, "INSERT INTO messages VALUES (?, 7, ?, ?)", -1, &insert, nullptr), SQLITE_OK);
    // Rows out of time order, two with the same timestamp: read by timestamp, then id.
    const std::vector<std::tuple<int, std::int64_t, float>> rows = {{1, 300, 3.f}, {2, 100, 1.f}, {4, 200, 2.5f}, {3, 200, 2.f}};
    for (const auto& [id, stamp, x] : rows) {
        const std::string blob = test::CdrCloud(0, std::uint32_t(stamp), {x, 0, 0});
        sqlite3_bind_int(insert, 1, id);
        sqlite3_bind_int64(insert, 2, stamp);
        sqlite3_bind_blob(insert, 3, blob.data(), int(blob.size()), SQLITE_TRANSIENT);
        ASSERT_EQ(sqlite3_step(insert), SQLITE_DONE);
        sqlite3_reset(insert);
    }
    sqlite3_finalize(insert);
    sqlite3_close(db);
    const auto scans = test::ReadAllScans(folder);
    ASSERT_EQ(scans.size(), 4u);
    EXPECT_EQ(scans[0].points[0].x(), 1.f);
    EXPECT_EQ(scans[1].points[0].x(), 2.f);
    EXPECT_EQ(scans[2].points[0].x(), 2.5f);
    EXPECT_EQ(scans[3].points[0].x(), 3.f);
    EXPECT_EQ(scans[3].stamp_ns, 300);
    EXPECT_EQ(test::ReadAllScans(folder / "bag_0.db3").size(), 4u);  // the .db3 file itself names its folder
}

TEST(Rosbag2Sqlite, NotADatabaseIsAnError) {
    test::TempDir dir;
    std::ofstream(dir / "metadata.yaml") << "rosbag2_bagfile_information:\n  version: 5\n";
    std::ofstream(dir / "x_0.db3") << std::string(5000, 'x');
    EXPECT_THROW(test::ReadAllScans(dir.path()), DatasetError);
}

#ifdef REVISIT_HAVE_ROSBAG
TEST(Ros1Bag, Lz4ChunksWrittenByRosbag) {
    test::TempDir dir;
    const auto file = dir / "lz4.bag";
    {
        rosbag::Bag bag(file.string(), rosbag::bagmode::Write);
        bag.setCompression(rosbag::compression::LZ4);
        for (int i = 0; i < 3; ++i) {
            const auto cloud = test::Ros1Cloud(ros::Time(100 + i, 250), "velodyne", {"x", "y", "z", "intensity"},
                                               {float(i), 1, 2, 9, 3, 4, 5, 8});
            bag.write("/velodyne_points", cloud.header.stamp, cloud);
        }
    }
    const auto scans = test::ReadAllScans(file);
    ASSERT_EQ(scans.size(), 3u);
    EXPECT_EQ(scans[2].points[0], Eigen::Vector3f(2, 1, 2));
    EXPECT_EQ(scans[2].points[1], Eigen::Vector3f(3, 4, 5));
    EXPECT_EQ(scans[2].intensities, (std::vector<float>{9, 8}));
    EXPECT_EQ(scans[1].stamp_ns, 101'000'000'250);
    EXPECT_EQ(scans[0].sensor_label, "velodyne");
}

TEST(Ros1Bag, NotABagIsAnError) {
    test::TempDir dir;
    std::ofstream(dir / "x.bag") << "#ROSBAG V2.0\n" << std::string(100, '\xff');
    EXPECT_THROW(test::ReadAllScans(dir / "x.bag"), DatasetError);
}
#endif

}  // namespace
}  // namespace revisit
