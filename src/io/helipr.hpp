#pragma once
/// HeLiPR (Jung et al., IJRR 2024): four LiDARs of one vehicle, recognized from the sequence folder;
/// docs/formats.md names the published layout.
#include <filesystem>
#include <memory>

#include "io/cloud_files.hpp"
#include "io/reader.hpp"

namespace revisit {

/// ROOT/LiDAR/<sensor>/<ns>.bin for one of Ouster, Velodyne, Avia, Aeva (ROOT, or one such folder:
/// that sensor).
bool IsHeLiPRFolder(const std::filesystem::path& path);

/// One .bin of `sensor` ("Ouster", "Velodyne", "Avia" or "Aeva"; the Aeva layout depends on the
/// file's stamp, as published), packed little-endian records. Throws DatasetError.
CloudData LoadHeLiPRBin(const std::filesystem::path& file, const std::string& sensor);

/// The sensor `options.sensor_label` names (any case; empty: Ouster, else the first of Velodyne,
/// Avia, Aeva present), its scans in stamp order, its reference LiDAR_GT/<sensor>_gt.txt (or
/// global_<sensor>_gt.txt; `ns x y z qx qy qz qw`, moved so the first position is the origin)
/// paired by time. Throws DatasetError.
std::unique_ptr<Reader> OpenHeLiPR(const std::filesystem::path& path, const ReaderOptions& options);

}  // namespace revisit
