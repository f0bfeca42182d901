#pragma once
/// Readers for folders of one-file-per-scan datasets: KITTI (velodyne/*.bin) and .pcd / .ply folders.
#include <memory>

#include "io/reader.hpp"

namespace revisit {

/// True when `path` looks like a KITTI sequence: it has velodyne/*.bin, or is such a velodyne folder.
bool IsKittiFolder(const std::filesystem::path& path);

/// KITTI sequence folder: velodyne/*.bin, optional poses.txt (or the official ../../poses/NN.txt),
/// calib.txt (Tr: poses converted from camera to LiDAR frame as Tr^-1 * P * Tr) and times.txt.
std::unique_ptr<Reader> OpenKittiFolder(const std::filesystem::path& path, const ReaderOptions& options);

/// A folder of .pcd or .ply scans, sorted by name, with optional poses.txt (KITTI or TUM) and times.txt.
std::unique_ptr<Reader> OpenCloudFolder(const std::filesystem::path& path, const ReaderOptions& options);

}  // namespace revisit
