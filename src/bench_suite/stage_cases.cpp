/// Front-end cases: reader throughput, odometry per scan (1 and 2 threads), local map update.
#include <tbb/global_control.h>

#include <cmath>

#include "bench_suite/cases.hpp"
#include "io/reader.hpp"
#include "io/writer.hpp"
#include "odometry/lidar_odometry.hpp"
#include "pipeline/odometry_stages.hpp"

namespace revisit {

namespace {
std::uintmax_t FolderBytes(const std::filesystem::path& path) {
    if (std::filesystem::is_regular_file(path)) return std::filesystem::file_size(path);
    std::uintmax_t bytes = 0;
    for (const auto& entry : std::filesystem::recursive_directory_iterator(path))
        if (entry.is_regular_file()) bytes += entry.file_size();
    return bytes;
}

/// Reads the whole dataset each run: MB/s of its files and scans/s.
void MeasureReader(const CaseContext& c, const std::string& label, const std::filesystem::path& path,
                   double laser_aperture, const std::string& note, const std::string& group = "reader") {
    ReaderOptions options;
    options.laser_aperture = laser_aperture;
    const double megabytes = double(FolderBytes(path)) / 1e6;
    std::size_t scans = 0;
    const auto read_all = [&] {
        auto reader = OpenDataset(path, options);
        scans = 0;
        while (reader->Next()) ++scans;
        return double(scans);
    };
    {
        Measurement measured =
            Measure(group + "/" + label + " scans", "scans/s", FigureKind::kItemsPerSecond, c.scale.repeat, read_all);
        c.Add(std::move(measured), note);
    }
    {
        Measurement measured = Measure(group + "/" + label + " MB", "MB/s", FigureKind::kItemsPerSecond, c.scale.repeat,
                                       [&] { return read_all() > 0 ? megabytes : 0.0; });
        c.Add(std::move(measured), note + ", " + std::to_string(megabytes).substr(0, 5) + " MB");
    }
}

/// Odometry over `scans` from a fresh state, per scan, with the TBB threads capped at `threads`.
/// Without odometry priors (the simulator attaches a drifting one): KITTI-like data has none, and the
/// constant-velocity guess is what `revisit run` sees on such folders.
void MeasureOdometry(const CaseContext& c, const std::string& label, std::vector<Scan> scans,
                     const OdometryConfig& config, const std::string& note) {
    if (scans.size() < 2) return c.Skip("odometry/" + label + ": fewer than 2 scans");
    for (auto& scan : scans) scan.T_odom_sensor.reset();
    PipelineConfig settings;
    settings.odometry = config;
    settings.input.follow_scene_scale = false;  // the crop stays the given one
    for (const int threads : {1, 2}) {
        const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, std::size_t(threads));
        std::size_t points = 0;
        for (const auto& s : scans) points += s.points.size();
        {
            Measurement measured = Measure("odometry/" + label + " " + std::to_string(threads) + "t", "ms/scan",
                                           FigureKind::kMsPerItem, c.scale.repeat, [&] {
                                               // As `revisit odometry` and `revisit run` register: the
                                               // preparation of later scans runs ahead.
                                               OdometryStages stages(settings);
                                               RunOdometryStages(stages, scans, [](OdometryStages::Item&, const Eigen::Isometry3d&) {});
                                               return double(scans.size());
                                           });
            c.Add(std::move(measured), note + ", " + std::to_string(scans.size()) + " scans, " +
                                           std::to_string(points / scans.size()) + " points/scan, " +
                                           std::to_string(threads) + " thread(s) allowed");
        }
    }
}
}  // namespace

void ReaderCases(const CaseContext& c) {
    const auto& sim = c.fixtures->Simulated("city-64", c.scale.odometry_scans);
    const auto folder = c.scratch_dir / "city64_kitti";
    {
        auto writer = CreateKittiWriter(folder, true);
        for (const auto& scan : sim) writer->Write(scan);
        writer->Finish();
    }
    MeasureReader(c, "sim city-64 KITTI", folder, 0.0, "simulated HDL-64E-like KITTI folder (float32 x y z i)");
    if (c.Need("kitti00_first16", "reader/kitti00_first16"))
        MeasureReader(c, "kitti00_first16", c.data_dir / "kitti00_first16", 0.0, "16 real HDL-64E scans, KITTI .bin");
    if (c.Need("radish/intel.rawlog", "reader/intel.rawlog"))
        MeasureReader(c, "intel.rawlog", c.data_dir / "radish/intel.rawlog", M_PI, "13,631 real 2D scans, MRPT rawlog");
    // The same 241 scans as a gzipped CARMEN log and as the KITTI folder converted from it.
    if (c.Need("carmen_kitti/seattle", "reader/carmen_kitti seattle"))
        MeasureReader(c, "carmen_kitti seattle", c.data_dir / "carmen_kitti/seattle", 0.0, "241 real 2D scans, KITTI .bin");
    if (c.Need("carmen/seattle-corrected.log.gz", "reader/seattle CARMEN log"))
        MeasureReader(c, "seattle CARMEN log", c.data_dir / "carmen/seattle-corrected.log.gz", 0.0,
                      "the same 241 scans, CARMEN log (gzip)");
}

void BagReaderCases(const CaseContext& c) {
    // The same 266 Livox scans as a KITTI folder and as each ROS bag format (../shared/data/bags).
    if (c.Need("livox_handheld_walk", "bag_reader/livox walk KITTI"))
        MeasureReader(c, "livox walk KITTI", c.data_dir / "livox_handheld_walk", 0.0, "266 Livox scans, KITTI .bin + poses.txt",
                      "bag_reader");
    const std::pair<const char*, const char*> bags[] = {
        {"livox_walk.mcap", "MCAP, zstd chunks"},          {"livox_walk_uncompressed.mcap", "MCAP, uncompressed chunks"},
        {"livox_walk_db3", "rosbag2 sqlite3 (Humble)"},    {"livox_walk.bag", "ROS 1 bag, uncompressed chunks"},
        {"livox_walk_bz2.bag", "ROS 1 bag, bz2 chunks"}};
    for (const auto& [name, note] : bags) {
        const std::string label = std::string("livox walk ") + name;
        if (c.Need(std::filesystem::path("bags") / name, "bag_reader/" + label))
            MeasureReader(c, label, c.data_dir / "bags" / name, 0.0, std::string("the same 266 scans + /odom + /ground_truth, ") + note,
                          "bag_reader");
    }
}

/// Scans [skip, skip + n) of a preset: the routes start from standstill, where ICP converges in a
/// couple of iterations and odometry looks faster than at cruising speed.
std::vector<Scan> Cruising(const CaseContext& c, const std::string& preset, std::size_t skip, std::size_t n) {
    const auto& all = c.fixtures->Simulated(preset, skip + n);
    return {all.begin() + std::ptrdiff_t(std::min(skip, all.size())), all.end()};
}

void OdometryCases(const CaseContext& c) {
    const std::size_t n = c.scale.odometry_scans, skip = c.scale.odometry_skip;
    MeasureOdometry(c, "sim 64-beam", Cruising(c, "city-64", skip, n), OdometryConfigFor("64-beam"),
                    "city-64 preset from scan " + std::to_string(skip));
    MeasureOdometry(c, "sim livox", Cruising(c, "campus-handheld", skip, n), OdometryConfigFor("livox"),
                    "campus-handheld preset (Livox Avia-like) from scan " + std::to_string(skip));
    MeasureOdometry(c, "sim 2d", Cruising(c, "indoor-2d-360", skip, 4 * n), OdometryConfigFor("2d"),
                    "indoor-2d-360 preset (720 beams) from scan " + std::to_string(skip));
    if (c.Need("kitti00_first16", "odometry/kitti00 64-beam"))
        MeasureOdometry(c, "kitti00 64-beam", c.fixtures->Dataset(c.data_dir / "kitti00_first16", 16),
                        OdometryConfigFor("64-beam"), "KITTI 00 scans 0-15");
    // From scan 2000 on: the log starts with the robot standing still.
    if (c.Need("radish/intel.rawlog", "odometry/intel 2d"))
        MeasureOdometry(c, "intel 2d", c.fixtures->Dataset(c.data_dir / "radish/intel.rawlog", 4 * n, M_PI, 2000),
                        OdometryConfigFor("2d"), "radish intel.rawlog from scan 2000, 180 beams");
}

void LocalMapCases(const CaseContext& c) {
    const auto& scans = c.fixtures->Simulated("city-64", c.scale.map_scans);
    {
        Measurement measured =
            Measure("local_map/update sim 64-beam", "ms/scan", FigureKind::kMsPerItem, c.scale.repeat, [&] {
                LocalMapper mapper;  // paper: 100 m maps of 1 m voxels (METHOD.md section 2)
                for (std::size_t i = 0; i < scans.size(); ++i)
                    mapper.AddScan(i, scans[i].points, *scans[i].T_world_sensor);
                mapper.Finish();
                return double(scans.size());
            });
        c.Add(std::move(measured),
              "LocalMapper::AddScan, city-64, " + std::to_string(scans.size()) + " scans, map closes included");
    }
}

}  // namespace revisit
