#pragma once
/// KITTI (3x4 row-major per line) and TUM (t x y z qx qy qz qw) trajectory files.
#include <filesystem>

#include "core/trajectory.hpp"

namespace revisit {

enum class PoseFormat { kKitti, kTum };

/// Reads a KITTI poses file (12 numbers per line); timestamps left empty. Throws DatasetError with the line.
Trajectory ReadKittiPoses(const std::filesystem::path& file);
/// Reads a TUM file; '#' comments and blank lines are skipped. Throws DatasetError with the line.
Trajectory ReadTumPoses(const std::filesystem::path& file);
/// Guesses the format from the first data line (12 vs 8 numbers) and reads it.
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

/// For each query time, the index of the trajectory entry with the nearest timestamp, or -1 when
/// the nearest is farther than max_dt [s]. Trajectory timestamps must be sorted.
std::vector<long> AssociateByTime(const std::vector<double>& trajectory_times,
                                  const std::vector<double>& query_times, double max_dt);

}  // namespace revisit
