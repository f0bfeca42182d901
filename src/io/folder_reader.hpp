#pragma once
/// Readers for folders of one-file-per-scan datasets: KITTI (velodyne/*.bin) and .pcd / .ply folders.
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "core/trajectory.hpp"
#include "io/cloud_files.hpp"
#include "io/reader.hpp"

namespace revisit {

/// True when `path` looks like a KITTI sequence: it has velodyne/*.bin, or is such a velodyne folder.
bool IsKittiFolder(const std::filesystem::path& path);

/// The `Tr:` line of a KITTI calib.txt (velodyne to left camera), if there is one; malformed: DatasetError.
std::optional<Eigen::Isometry3d> ReadKittiTr(const std::filesystem::path& calib);

/// KITTI sequence folder: velodyne/*.bin, optional poses.txt (or the official ../../poses/NN.txt),
/// calib.txt (Tr: poses converted from camera to LiDAR frame as Tr^-1 * P * Tr) and times.txt.
std::unique_ptr<Reader> OpenKittiFolder(const std::filesystem::path& path, const ReaderOptions& options);

/// A folder of .pcd or .ply scans, sorted by name, with optional poses.txt (KITTI or TUM) and times.txt.
std::unique_ptr<Reader> OpenCloudFolder(const std::filesystem::path& path, const ReaderOptions& options);

/// One scan per file of `files` (in order) read by `loader`, stamped by `times` (one per file), with
/// `reference` (time-stamped, TUM-like) paired by time stamp (io/timed_poses.hpp): the public
/// dataset layouts (io/public_layouts.hpp) are this.
using CloudLoader = CloudData (*)(const std::filesystem::path&);
std::unique_ptr<Reader> OpenStampedScanFiles(DatasetInfo info, std::vector<std::filesystem::path> files, CloudLoader loader,
                                             std::string label, std::vector<double> times, Trajectory reference,
                                             const ReaderOptions& options);

}  // namespace revisit
