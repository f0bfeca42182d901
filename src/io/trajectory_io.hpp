#pragma once
/// KITTI (3x4 row-major per line) and TUM (t x y z qx qy qz qw) trajectory files.
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "core/trajectory.hpp"

namespace revisit {

enum class PoseFormat { kKitti, kTum };

/// Reads a KITTI poses file (12 numbers per line); timestamps left empty. Throws DatasetError with the line.
Trajectory ReadKittiPoses(const std::filesystem::path& file);
/// Reads a TUM file; '#' comments and blank lines are skipped. Throws DatasetError with the line.
Trajectory ReadTumPoses(const std::filesystem::path& file);
/// Reads `#sec,nsec,x,y,z,qx,qy,qz,qw` lines (Newer College's ground truth): time = sec + nsec * 1e-9 [s].
Trajectory ReadSecNsecPoses(const std::filesystem::path& file);
/// Guesses the format from the first data line (12 or 8 numbers, or 9 comma-separated) and reads it.
Trajectory ReadPoses(const std::filesystem::path& file);
/// Reads KITTI times.txt (one time [s] per line).
std::vector<double> ReadTimes(const std::filesystem::path& file);

/// Writes with 9 significant digits after the point (precise to ~1e-9 m), `\n` line ends.
void WriteKittiPoses(const std::filesystem::path& file, const Poses& poses);
void WriteTumPoses(const std::filesystem::path& file, const Trajectory& trajectory);
void WriteTimes(const std::filesystem::path& file, const std::vector<double>& timestamps);

/// A pose and a time exactly as WriteKittiPoses / WriteTimes store them and the readers read them back
/// (9 decimals): what a dataset written to disk holds, for readers that make their data in memory.
Eigen::Isometry3d AsStoredKittiPose(const Eigen::Isometry3d& T);
double AsStoredTime(double t);
/// A pose exactly as WriteTumPoses stores it and ReadTumPoses reads it back (a run folder's reference).
Eigen::Isometry3d AsStoredTumPose(const Eigen::Isometry3d& T);

/// How the data lines of a numeric text file look; blank lines and '#' comments are always skipped.
struct NumberLines {
    std::size_t count = 0;        ///< numbers per data line
    std::string what;             ///< for messages: "malformed <what> line"
    bool csv = false;             ///< commas separate the numbers
    bool skip_nan_lines = false;  ///< lines holding "nan" are skipped (some datasets mark missing poses so)
};
/// Calls `on_values(values, line_number)` for every data line; a line with another count of numbers,
/// a token that is not a number or an infinite value is a DatasetError naming the line.
void ForEachNumberLine(const std::filesystem::path& file, const NumberLines& format,
                       const std::function<void(const std::vector<double>&, std::size_t)>& on_values);
/// A pose from a text file's rounded rotation; a matrix (or quaternion) far from a rotation is a
/// DatasetError naming the line.
Eigen::Isometry3d CleanPose(const Eigen::Matrix3d& R, const Eigen::Vector3d& t, const std::filesystem::path& file,
                            std::size_t line_number);
Eigen::Isometry3d CleanPose(const Eigen::Quaterniond& q, const Eigen::Vector3d& t, const std::filesystem::path& file,
                            std::size_t line_number);
/// Appends (t, T); a time before the previous one is a DatasetError naming the line.
void AppendStampedPose(Trajectory& trajectory, double t, const Eigen::Isometry3d& T, const std::filesystem::path& file,
                       std::size_t line_number);

/// For each query time, the index of the trajectory entry with the nearest timestamp, or -1 when
/// the nearest is farther than max_dt [s]. Trajectory timestamps must be sorted.
std::vector<long> AssociateByTime(const std::vector<double>& trajectory_times,
                                  const std::vector<double>& query_times, double max_dt);

}  // namespace revisit
