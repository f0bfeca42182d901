#pragma once
/// Public datasets recognized from their folder layout, each read with its reference poses paired by
/// time stamp (io/timed_poses.hpp). docs/formats.md names each layout's source.
#include <filesystem>
#include <memory>

#include "io/reader.hpp"

namespace revisit {

/// MulRan (Kim et al., ICRA 2020): ROOT/global_pose.csv and ROOT/sensor_data/Ouster/<ns>.bin (or ROOT/Ouster/).
bool IsMulRanFolder(const std::filesystem::path& path);

/// Scans from the Ouster .bin files (KITTI layout: float32 x, y, z, intensity) in the order of the
/// nanosecond stamps that name them; reference poses from global_pose.csv (nanosecond stamp, then a
/// 3x4 row-major pose, comma-separated), moved so the first pose is at the origin. Throws DatasetError.
std::unique_ptr<Reader> OpenMulRan(const std::filesystem::path& path, const ReaderOptions& options);

}  // namespace revisit
