#pragma once
/// Newer College (Ramezani et al., IROS 2020) and its 2021 extension, recognized from the sequence
/// folder; docs/formats.md names the published layout.
#include <filesystem>
#include <memory>

#include "io/reader.hpp"

namespace revisit {

/// ROOT/raw_format/ouster_scan/cloud_<sec>_<nsec>.pcd (or ROOT/ouster_scan/).
bool IsNewerCollegeFolder(const std::filesystem::path& path);

/// Scans from the Ouster PCDs in the order of the stamps that name them; reference poses from
/// ROOT/ground_truth/registered_poses.csv (2020) or the one gt-nc-*.csv / gt_state_*.csv (2021 extension),
/// `#sec,nsec,x,y,z,qx,qy,qz,qw` lines, paired by time. No ground truth: no reference. Throws DatasetError.
std::unique_ptr<Reader> OpenNewerCollege(const std::filesystem::path& path, const ReaderOptions& options);

}  // namespace revisit
