/// Writes the seed corpus of every fuzz target with the project's own writers (small files):
/// `fuzz_seeds DIR` fills DIR/<target>/. Targets whose first byte selects a reader get it prefixed.
#include <bzlib.h>
#include <zlib.h>

#include <cmath>
#include <fstream>
#include <iostream>
#include <sstream>

#include "closures/database_io.hpp"
#include "core/error.hpp"
#include "io/cloud_files.hpp"
#include "io/trajectory_io.hpp"
#include "io/writer.hpp"
#include "config/config.hpp"
#include "runfolder/map_points_file.hpp"
#include "runfolder/run_files.hpp"
#include "../io/mcap_test_writer.hpp"

#include <sqlite3.h>
#ifdef REVISIT_HAVE_ROSBAG
#include <nav_msgs/Odometry.h>
#include <rosbag/bag.h>
#include "../support/ros1_cloud.hpp"
#endif

namespace {
namespace fs = std::filesystem;
using namespace revisit;

std::string ReadBytes(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void Seed(const fs::path& dir, const std::string& name, int selector, const std::string& bytes) {
    fs::create_directories(dir);
    std::ofstream out(dir / name, std::ios::binary);
    if (selector >= 0) out.put(static_cast<char>(selector));
    out << bytes;
}

/// ROS bag seeds: two small clouds and a pose per format (MCAP plain, lz4 and cut; db3; ROS 1 bags).
void BagSeeds(const fs::path& out, const fs::path& tmp) {
    using namespace revisit::test;
    std::string pose = Bytes().Raw(std::string("\0\1\0\0", 4)).data;
    Bytes ps;
    ps.origin = 4;
    ps.Raw(pose).Put(std::int32_t(1), true).Put(std::uint32_t(5), true).CdrStr("map");
    for (double v : {1.0, 2.0, 3.0, 0.0, 0.0, 0.0, 1.0}) ps.Put(v, true);
    const std::string records = Schema(1, "sensor_msgs/msg/PointCloud2") + Schema(2, "geometry_msgs/msg/PoseStamped") +
                                Channel(0, 1, "/points") + Channel(1, 2, "/gt") + Message(0, 1, CdrCloud(1, 5, {1, 2, 3, 4, 5, 6})) +
                                Message(1, 1, ps.data) + Message(0, 2, CdrCloud(2, 5, {7, 8, 9}));
    const std::string plain = Mcap(Chunk(records, ""));
    Seed(out / "fuzz_mcap", "plain", -1, plain);
    Seed(out / "fuzz_mcap", "lz4", -1, Mcap(Chunk(records, "lz4")));
    Seed(out / "fuzz_mcap", "unchunked", -1, Mcap(records));
    Seed(out / "fuzz_mcap", "cut", -1, plain.substr(0, plain.size() - 60));
    // db3: Humble's tables with the same messages.
    sqlite3* db = nullptr;
    const fs::path db3 = tmp / "seed.db3";
    fs::remove(db3);
    if (sqlite3_open(db3.c_str(), &db) != SQLITE_OK) throw std::runtime_error("sqlite3_open");
    const std::string cloud = CdrCloud(1, 5, {1, 2, 3});
    std::string sql =
        "CREATE TABLE schema(schema_version INTEGER PRIMARY KEY, ros_distro TEXT NOT NULL); INSERT INTO schema VALUES (3, 'humble');"
        "CREATE TABLE topics(id INTEGER PRIMARY KEY, name TEXT NOT NULL, type TEXT NOT NULL, serialization_format TEXT NOT NULL,"
        " offered_qos_profiles TEXT NOT NULL);"
        "CREATE TABLE messages(id INTEGER PRIMARY KEY, topic_id INTEGER NOT NULL, timestamp INTEGER NOT NULL, data BLOB NOT NULL);"
        "INSERT INTO topics VALUES (1, '/points', 'sensor_msgs/msg/PointCloud2', 'cdr', ''),"
        " (2, '/gt', 'geometry_msgs/msg/PoseStamped', 'cdr', '');";
    sqlite3_exec(db, sql.c_str(), nullptr, nullptr, nullptr);
    sqlite3_stmt* insert = nullptr;
    sqlite3_prepare_v2(db, "INSERT INTO messages (topic_id, timestamp, data) VALUES (?, ?, ?)", -1, &insert, nullptr);
    for (const auto& [topic, blob] : {std::make_pair(1, cloud), std::make_pair(2, ps.data)}) {
        sqlite3_bind_int(insert, 1, topic);
        sqlite3_bind_int64(insert, 2, 1'000'000'005);
        sqlite3_bind_blob(insert, 3, blob.data(), int(blob.size()), SQLITE_TRANSIENT);
        sqlite3_step(insert);
        sqlite3_reset(insert);
    }
    sqlite3_finalize(insert);
    sqlite3_close(db);
    Seed(out / "fuzz_db3", "humble", -1, ReadBytes(db3));
#ifdef REVISIT_HAVE_ROSBAG
    for (const auto& [name, compression] : {std::make_pair("plain", rosbag::compression::Uncompressed),
                                            std::make_pair("bz2", rosbag::compression::BZ2),
                                            std::make_pair("lz4", rosbag::compression::LZ4)}) {
        const fs::path file = tmp / (std::string(name) + ".bag");
        {
            rosbag::Bag bag(file.string(), rosbag::bagmode::Write);
            bag.setCompression(compression);
            for (int i = 0; i < 2; ++i) {
                // The bytes of each point all i (x = y = z, as the seeds always had).
                float value = 0.f;
                std::memset(&value, i, 4);
                const auto msg = test::Ros1Cloud(ros::Time(10 + i, 0), "lidar", {"x", "y", "z"}, {value, value, value});
                bag.write("/points", msg.header.stamp, msg);
                nav_msgs::Odometry odom;
                odom.header = msg.header;
                odom.child_frame_id = "lidar";
                odom.pose.pose.orientation.w = 1;
                bag.write("/odom", msg.header.stamp, odom);
            }
        }
        Seed(out / "fuzz_ros1", name, -1, ReadBytes(file));
    }
#endif
}

Scan MakeScan(int index) {
    Scan scan;
    scan.timestamp = 0.1 * index;
    for (int i = 0; i < 24; ++i) {
        const double angle = i * 0.26;
        scan.points.emplace_back(float(5 * std::cos(angle)), float(5 * std::sin(angle)), float(0.1 * index));
        scan.intensities.push_back(float(i));
    }
    scan.T_world_sensor = Eigen::Isometry3d(Eigen::Translation3d(index, 0, 0));
    scan.T_odom_sensor = scan.T_world_sensor;
    return scan;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 2) {
        std::cerr << "usage: fuzz_seeds DIR\n";
        return 2;
    }
    const fs::path out = argv[1];
    const fs::path tmp = out / "tmp";
    fs::create_directories(tmp);
    try {
        // Scans: KITTI .bin, PCD ascii and binary, PLY binary and ascii.
        SaveKittiBin(tmp / "s.bin", MakeScan(0));
        Seed(out / "fuzz_scans", "bin", 0, ReadBytes(tmp / "s.bin"));
        Seed(out / "fuzz_scans", "pcd-ascii", 1,
             "VERSION 0.7\nFIELDS x y z intensity\nSIZE 4 4 4 4\nTYPE F F F F\nCOUNT 1 1 1 1\nWIDTH 2\nHEIGHT 1\n"
             "POINTS 2\nDATA ascii\n1 2 3 0.5\n4 5 6 1\n");
        std::string binary_points(2 * 16, '\0');
        Seed(out / "fuzz_scans", "pcd-binary", 1,
             "FIELDS x y z t\nSIZE 4 4 4 4\nTYPE F F F F\nWIDTH 2\nHEIGHT 1\nDATA binary\n" + binary_points);
        SavePly(tmp / "s.ply", MakeScan(1).points, MakeScan(1).intensities);
        Seed(out / "fuzz_scans", "ply-binary", 2, ReadBytes(tmp / "s.ply"));
        Seed(out / "fuzz_scans", "ply-ascii", 2,
             "ply\nformat ascii 1.0\nelement face 1\nproperty list uchar int v\nelement vertex 2\nproperty float x\n"
             "property float y\nproperty float z\nend_header\n3 0 1 2\n1 2 3\n4 5 6\n");
        // NCLT (8-byte) and HeLiPR (26, 22, 19, 29-byte) records: two points each.
        const int record_bytes[] = {8, 26, 22, 19, 29};
        const char* const record_names[] = {"nclt", "helipr-ouster", "helipr-velodyne", "helipr-avia", "helipr-aeva"};
        for (int i = 0; i < 5; ++i) {
            std::string records(2 * static_cast<std::size_t>(record_bytes[i]), '\0');
            for (std::size_t b = 0; b < records.size(); ++b) records[b] = static_cast<char>(b * 37 % 251);
            Seed(out / "fuzz_scans", record_names[i], 3 + i, records);
        }
        // Trajectories, times, calib.
        Trajectory trajectory;
        for (int i = 0; i < 3; ++i) {
            trajectory.poses.push_back(*MakeScan(i).T_world_sensor);
            trajectory.timestamps.push_back(0.1 * i);
        }
        WriteKittiPoses(tmp / "k.txt", trajectory.poses);
        WriteTumPoses(tmp / "t.txt", trajectory);
        WriteTimes(tmp / "times.txt", trajectory.timestamps);
        Seed(out / "fuzz_trajectories", "kitti", 0, ReadBytes(tmp / "k.txt"));
        Seed(out / "fuzz_trajectories", "tum", 0, ReadBytes(tmp / "t.txt"));
        Seed(out / "fuzz_trajectories", "times", 1, ReadBytes(tmp / "times.txt"));
        Seed(out / "fuzz_trajectories", "sec-nsec-csv", 0,
             "#sec,nsec,x,y,z,qx,qy,qz,qw\n1583836591, 182590976, 1.0, 2.0, 0.5, 0, 0, 0, 1\n"
             "1583836591, 282590976, 1.5, 2.0, 0.5, 0, 0, 0.0998, 0.995\n");
        Seed(out / "fuzz_trajectories", "calib", 2, "P0: 1 0 0 0 0 1 0 0 0 0 1 0\nTr: 1 0 0 0.1 0 1 0 0 0 0 1 -0.2\n");
        // Rawlogs: plain and gzip, point clouds and 2D range scans with odometry and ground truth.
        for (const char* name : {"r.rawlog", "r.rawlog.gz", "planar.rawlog"}) {
            WriterOptions options;
            options.planar_as_range_scan = std::string(name) == "planar.rawlog";
            options.planar_beams = 32;
            auto writer = CreateRawlogWriter(tmp / name, options);
            for (int i = 0; i < 2; ++i) writer->Write(MakeScan(i));
            writer->Finish();
            Seed(out / "fuzz_rawlog", name, -1, ReadBytes(tmp / name));
        }
        // CARMEN logs: FLASER/RLASER/ODOM/PARAM lines, a ROBOTLASER1 line; plain, gzip and bzip2.
        const std::string carmen =
            "PARAM robot_front_laser_max 10.0 nohost 0\nODOM 0 0 0 0 0 0 100.0 host 100.0\n"
            "FLASER 5 1.0 2.0 10.0 0.01 4.0 0.5 0.25 0.1 0.5 0.25 0.1 100.5 host 100.5\n"
            "RLASER 3 1 1 1 0 0 3.14 0 0 0 100.6 host 100.6\n"
            "FLASER 5 3.0 3.0 3.0 3.0 3.0 1.5 0.25 0.2 1.5 0.25 0.2 101.0 host 101.0\n";
        const std::string robot_laser =
            "ROBOTLASER1 0 -0.785398 1.570796 0.785398 5.0 0.1 0 3 1.0 5.0 2.0 2 7 8 1.2 0 0 1 0 0 0 0 0 0 0 55.5 host 55.5\n";
        Seed(out / "fuzz_carmen", "flaser", 0, carmen);
        Seed(out / "fuzz_carmen", "robotlaser", 3, robot_laser);
        {
            std::string gz(compressBound(carmen.size()) + 64, '\0');
            z_stream z{};
            deflateInit2(&z, Z_DEFAULT_COMPRESSION, Z_DEFLATED, 16 + MAX_WBITS, 8, Z_DEFAULT_STRATEGY);
            z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(carmen.data()));
            z.avail_in = static_cast<uInt>(carmen.size());
            z.next_out = reinterpret_cast<Bytef*>(gz.data());
            z.avail_out = static_cast<uInt>(gz.size());
            deflate(&z, Z_FINISH);
            gz.resize(z.total_out);
            deflateEnd(&z);
            Seed(out / "fuzz_carmen", "gzip", 0, gz);
            std::string bz(carmen.size() + 1024, '\0');
            unsigned length = static_cast<unsigned>(bz.size());
            BZ2_bzBuffToBuffCompress(bz.data(), &length, const_cast<char*>(carmen.data()), static_cast<unsigned>(carmen.size()), 9, 0, 0);
            bz.resize(length);
            Seed(out / "fuzz_carmen", "bzip2", 0, bz);
        }
        // database.bin with one map.
        ClosureDetector detector;
        LocalMap map;
        for (int i = 0; i < 4000; ++i) {
            map.points.emplace_back(float((i * 37) % 200) * 0.25f, float((i * 91) % 160) * 0.25f, 0.f);
        }
        detector.AddMap(map);
        SaveDatabase(detector, tmp / "database.bin");
        Seed(out / "fuzz_database", "database", -1, ReadBytes(tmp / "database.bin"));
        // A local map's points (maps/map_NNNN.rvmap) at a 0.5 m map voxel.
        Seed(out / "fuzz_map_points", "map", -1, EncodeMapPoints(map.points, MapPointStep(0.5)));
        // Configs: the defaults and a preset-like override file.
        Seed(out / "fuzz_config", "default", -1, DumpConfig(PipelineConfig{}));
        Seed(out / "fuzz_config", "small", -1, "density:\n  resolution: 0.2\nodometry:\n  planar: true\n");
        // Run folder files (run.json, poses, local_maps.csv, closures.csv, timings.json, a closure detail).
        RunFolder run(tmp / "run");
        fs::create_directories(run.root() / "closures");
        RunState state;
        state.dataset = "seq";
        state.format = "kitti";
        state.poses_source = "odometry";
        state.complete = true;
        state.timestamps = trajectory.timestamps;
        state.odometry = state.corrected = trajectory.poses;
        MapRecordSummary summary;
        summary.last_scan = 2;
        summary.density_resolution = 0.5;
        state.maps = {summary, summary};
        state.maps[1].id = 1;
        ClosureRecord record;
        record.closure.query_id = 1;
        record.closure.query_keypoints = {{1, 2}, {3, 4}};
        record.closure.ref_keypoints = {{5, 6}};
        record.closure.matches = {{0, 0, 12}, {1, 0, 40}};
        record.closure.inlier_mask = {1, 0};
        state.closures = {record};
        state.timings["read"] = {1.0, 3};
        WriteRunState(run, state);
        const fs::path files[] = {run.run_info(), run.odometry_tum(), run.corrected_kitti(), run.local_maps_csv(),
                                  run.closures_csv(), run.timings_json(), run.root() / "closures" / "0000.json"};
        for (int i = 0; i < 7; ++i) Seed(out / "fuzz_run_folder", "file" + std::to_string(i), i, ReadBytes(files[i]));
        BagSeeds(out, tmp);
    } catch (const std::exception& e) {
        std::cerr << "fuzz_seeds: " << e.what() << '\n';
        return 1;
    }
    fs::remove_all(tmp);
    return 0;
}
