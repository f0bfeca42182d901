#pragma once
/// Streaming dataset readers: one scan at a time, never the whole sequence in memory.
#include <cstddef>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/scan.hpp"
#include "io/timed_poses.hpp"

namespace revisit {

struct ReaderOptions {
    std::string sensor_label;                ///< rawlogs: keep only this sensor label (empty: all)
    bool kitti_vertical_correction = false;  ///< rotate KITTI points by 0.205 deg about the axis normal to their azimuth
    std::filesystem::path poses_file;        ///< reference poses (KITTI 3x4 or TUM) overriding the dataset's own
    /// TUM reference poses pair with scans by time stamp (KITTI ones by index): tolerance and gaps.
    TimePairingConfig pose_pairing;
    /// 2D laser scans: field of view [rad] to use instead of the file's `aperture` (0: the file's).
    /// Some converted logs store a wrong aperture, e.g. the radish intel.rawlog says 90 deg for its
    /// 180-beam, 180-degree SICK scans, which bends every scan.
    double laser_aperture = 0.0;
    /// Rawlogs: a damaged or truncated file ends the sequence where reading stopped (DatasetInfo::truncated
    /// says why) instead of an error.
    bool allow_truncated = false;
    /// ROS bags (io/bag_reader.hpp): the topics to read; empty: the only topic of a fitting type; "none":
    /// no odometry prior / no reference poses.
    std::string points_topic;     ///< sensor_msgs PointCloud2 or LaserScan
    std::string odometry_topic;   ///< nav_msgs/Odometry: the odometry prior
    std::string reference_topic;  ///< geometry_msgs/PoseStamped, nav_msgs/Path or nav_msgs/Odometry: reference poses
    double reference_tolerance = 0.05;  ///< [s] ROS bags: a scan gets a reference pose stamped at most this far from it
};

/// A recording's topic (ROS bags), as `revisit info` lists them.
struct TopicSummary {
    std::string name;
    std::string type;
    std::size_t messages = 0;
    double rate_hz = 0.0;  ///< [Hz] messages over the span of their receive times (0: fewer than 2)
    std::string role;      ///< "points", "odometry", "reference", "static transforms" or "unused"
};

struct DatasetInfo {
    std::string format;                    ///< "kitti", "pcd", "ply", "rawlog", "carmen", "mcap", "rosbag2 sqlite3", "rosbag1", "mulran", "newer college", "nclt" or "helipr"
    std::filesystem::path path;            ///< what the user gave
    std::optional<std::size_t> num_scans;  ///< known up front for folders; rawlogs count while reading
    bool has_reference_poses = false;      ///< known up front (folders); rawlogs: after reading
    std::filesystem::path poses_file;      ///< where reference poses came from, if any
    std::string truncated;                 ///< with allow_truncated: why reading stopped early (empty: it did not)
    std::vector<TopicSummary> topics;      ///< ROS bags: every topic and the role revisit gives it
    std::string timing;                    ///< how the scans were stamped when the file has no times (empty: the file's)
};

/// What a reader dropped or skipped, so the user can be told once at the end.
struct ReadStats {
    std::size_t scans = 0;
    std::size_t points = 0;
    std::size_t non_finite_points = 0;                  ///< NaN/inf points dropped
    std::map<std::string, std::size_t> skipped_classes;  ///< rawlog objects that carry no scan
    std::map<std::string, std::size_t> skipped_sensors;  ///< scans filtered out by sensor label
};

class Reader {
  public:
    virtual ~Reader() = default;
    /// The next scan, or nullopt at the end. Throws DatasetError on corrupt input.
    virtual std::optional<Scan> Next() = 0;
    /// Where the format can go to a scan without reading the ones before it (a folder of scan files,
    /// the public datasets' sequence folders, the simulator): makes the first scan whose index is at
    /// least `index` the next one and returns true; the scans passed count in Stats().scans as read.
    /// A stream (a bag, a rawlog, a log file) returns false and the caller reads and drops them
    /// (pipeline/read_from.hpp).
    virtual bool SkipTo(std::size_t index) {
        (void)index;
        return false;
    }
    virtual const DatasetInfo& Info() const = 0;
    const ReadStats& Stats() const { return stats_; }

  protected:
    ReadStats stats_;
};

/// Datasets named by a scheme instead of a path, e.g. "sim:demo" (the simulator, registered by
/// sim/sim_reader.hpp). `spec` is the whole name, scheme included.
using DatasetOpener = std::function<std::unique_ptr<Reader>(const std::string& spec, const ReaderOptions& options)>;
void RegisterDatasetScheme(const std::string& scheme, DatasetOpener opener);
/// True when `path` names a registered scheme ("sim:..."): not a file, never made absolute.
bool IsSchemeDataset(const std::filesystem::path& path);
/// What a run records as its dataset: the absolute path, or the scheme name unchanged.
std::string DatasetName(const std::filesystem::path& path);

/// Picks the reader from the path: a registered scheme ("sim:PRESET"), a public dataset's sequence folder
/// (MulRan, Newer College, NCLT, HeLiPR), a folder with velodyne/ (or sequences/NN + poses/NN.txt),
/// a folder of .pcd or .ply files, a .rawlog / .rawlog.gz file, a CARMEN log (.log / .clf, plain, .gz
/// or .bz2), or a ROS bag: .mcap, ROS 1 .bag, or a rosbag2 folder (metadata.yaml + .db3). Throws DatasetError.
std::unique_ptr<Reader> OpenDataset(const std::filesystem::path& path, const ReaderOptions& options = {});

/// One line summary of ReadStats' drops and skips, empty when nothing was dropped.
std::string DescribeDrops(const ReadStats& stats);

}  // namespace revisit
