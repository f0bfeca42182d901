#pragma once
/// NCLT, the University of Michigan North Campus Long-Term dataset (Carlevaris-Bianco et al., IJRR
/// 2016), recognized from a session folder; docs/formats.md names the published layout.
#include <filesystem>
#include <memory>

#include "io/cloud_files.hpp"
#include "io/reader.hpp"

namespace revisit {

/// ROOT/velodyne_sync/<us>.bin (ROOT is a session, e.g. 2012-01-08/), or that velodyne_sync folder.
bool IsNcltFolder(const std::filesystem::path& path);

/// One velodyne_sync file: 8 bytes a point, little-endian uint16 x, y, z (metres = value * 0.005 -
/// 100), uint8 intensity, uint8 laser id. NCLT's frames have z down: the points come out turned by
/// 180 degrees about x (y and z negated) so that z is up. Throws DatasetError.
CloudData LoadNcltBin(const std::filesystem::path& file);

/// Scans in the order of their microsecond stamps; reference poses from groundtruth_<session>.csv
/// (utime [us], x, y, z, roll, pitch, yaw [rad]; its rows of NaN skipped) in ROOT, ROOT/.. or
/// ROOT/../ground_truth, turned z-up like the points, paired by time. Throws DatasetError.
std::unique_ptr<Reader> OpenNclt(const std::filesystem::path& path, const ReaderOptions& options);

}  // namespace revisit
