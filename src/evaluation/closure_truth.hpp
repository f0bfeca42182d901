#pragma once
/// Truth of accepted closures where reference poses exist, and revisit coverage: "were my revisits
/// found?" (issue 16). A closure is true when its relative pose agrees with the reference relative pose
/// where it was measured: at its anchor, the two scans (one of each map) that lie nearest each other
/// under the closure's own pose (METHOD.md section 7, "Where a closure is judged").
#include <cstddef>
#include <utility>
#include <vector>

#include "core/trajectory.hpp"
#include "evaluation/map_closure.hpp"
#include "evaluation/map_metrics.hpp"

namespace revisit {

struct ClosureTruthConfig {
    double true_translation = 0.5;   ///< [m] a closure is true within this planar translation error
    double true_rotation_deg = 2.0;  ///< [deg] and this yaw error
    double revisit_radius = 3.0;     ///< [m] a scan revisits when this close to an earlier scan
    double revisit_gap = 20.0;       ///< [m] of travel at least between the two
};

struct ClosureVerdict {
    bool is_true = false;
    ClosurePoseError error;             ///< at the anchor: decides `is_true`
    std::size_t query_scan = 0;         ///< the anchor's scan of the query map
    std::size_t ref_scan = 0;           ///< the anchor's scan of the reference map
    ClosurePoseError first_scan_error;  ///< at the maps' first scans (adds the odometry's error within each map)
};

/// A closure's anchor: the scan of each map nearest the other map's scans under the closure's pose
/// (scan positions from `T_odom_sensor`, the poses the maps were built from, within each map), the first
/// such pair in scan order; and the closure's relative pose between those two scans.
struct ClosureAnchor {
    std::size_t query_scan = 0;
    std::size_t ref_scan = 0;
    Eigen::Isometry3d T_query_scan_ref_scan = Eigen::Isometry3d::Identity();
};
ClosureAnchor AnchorOf(const MapClosureForEval& closure, const Poses& T_odom_sensor);

struct ClosureTruth {
    std::vector<ClosureVerdict> verdicts;  ///< one per input closure
    std::size_t num_true = 0;
    std::size_t num_false = 0;
};

/// Judges each closure at its anchor (AnchorOf over `T_odom_sensor`, the poses the maps were built from,
/// one per scan). Without them (empty), at the maps' first scans.
ClosureTruth JudgeClosures(const std::vector<MapClosureForEval>& closures, const Poses& T_world_reference,
                           const ClosureTruthConfig& config, const Poses& T_odom_sensor = {});

struct RevisitCoverage {
    std::size_t revisit_scans = 0;  ///< scans within revisit_radius of a scan passed >= revisit_gap earlier
    std::size_t covered_scans = 0;  ///< of those, in a map joined by a true closure to a map holding such a scan
    double coverage = 0.0;          ///< covered / revisit (0 when nothing revisits)
};

/// For every scan, the earlier scans it revisits (reference positions, travel along the reference path).
std::vector<std::vector<std::size_t>> FindRevisits(const Poses& T_world_reference, double radius, double gap);

/// `revisits` from FindRevisits (found once, scored for any set of closures); `maps` sorted by first
/// scan, disjoint; `true_map_pairs` hold indices into `maps` (either order).
RevisitCoverage ComputeRevisitCoverage(const std::vector<std::vector<std::size_t>>& revisits, const std::vector<MapRange>& maps,
                                       const std::vector<std::pair<std::size_t, std::size_t>>& true_map_pairs);

}  // namespace revisit
