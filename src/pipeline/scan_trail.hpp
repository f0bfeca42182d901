#pragma once
/// Where a local map's scans were, for telling a revisit from the boundary two consecutive maps share.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <vector>

namespace revisit {

/// A map's scans: their positions in the map frame and the sequence's travel [m] at each.
struct ScanTrail {
    std::vector<Eigen::Vector3d> positions_in_map;
    std::vector<double> travel;  ///< [m] nondecreasing
};

/// The trail of scans posed by `T_map_scan` (the first at the map origin), travel counted from `travel_start`.
ScanTrail MakeScanTrail(const std::vector<Eigen::Isometry3d>& T_map_scan, double travel_start);

/// Whether `later` (a map after `earlier`) comes back to where `earlier` went: a scan of each within
/// `radius` [m] of the other, at least `gap` [m] of travel apart, with the maps placed by
/// T_world_earlier and T_world_later. The scans where one map ends and the next begins are close in
/// travel, so a boundary alone is no revisit.
bool TrailRevisits(const ScanTrail& earlier, const Eigen::Isometry3d& T_world_earlier, const ScanTrail& later,
                   const Eigen::Isometry3d& T_world_later, double radius, double gap);

}  // namespace revisit
