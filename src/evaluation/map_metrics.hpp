#pragma once
/// Map-level quality of detected closures: was the right earlier map found, and how accurate is the
/// 2D relative pose against ground truth (issue 7; thesis section 5.2 reports the same for real data).
#include "core/trajectory.hpp"
#include "evaluation/map_closure.hpp"
#include "evaluation/scan_pair.hpp"
#include "evaluation/statistics.hpp"

#include <vector>

namespace revisit {

struct MapMetricsConfig {
    double min_inliers = 10.0;  ///< gamma: only closures accepted at this threshold are assessed
};

struct MapClosureAssessment {
    std::size_t closure = 0;           ///< index into the input closures
    std::size_t gt_scan_pairs = 0;     ///< ground-truth scan pairs between the two maps' scans
    bool right_map = false;            ///< gt_scan_pairs > 0: the maps really overlap
    double translation_error = 0.0;    ///< [m] planar (x, y) part of T_gt^-1 * T_est
    double yaw_error_deg = 0.0;        ///< [deg] |yaw| of T_gt^-1 * T_est
};

struct MapMetrics {
    std::vector<MapClosureAssessment> closures;  ///< the assessed (accepted) closures, in input order
    std::size_t num_right_maps = 0;
    double fraction_right = 0.0;             ///< num_right_maps / assessed closures (0 when none)
    ErrorStatistics translation_error;       ///< [m] over right-map closures only
    ErrorStatistics yaw_error_deg;           ///< [deg] over right-map closures only
};

/// Error of an estimated map-to-map pose against ground truth: planar translation and yaw.
struct ClosurePoseError {
    double translation = 0.0;  ///< [m] planar (x, y) part of T_gt^-1 * T_est
    double yaw_deg = 0.0;      ///< [deg] |yaw| of T_gt^-1 * T_est
};
/// T_gt_query_ref = T_world_sensor[query_first]^-1 * T_world_sensor[ref_first] (map frames are the frames of
/// the maps' first scans). Throws ConfigError when a scan has no reference pose.
ClosurePoseError ClosureErrorAgainst(const Poses& T_world_sensor, std::size_t query_first_scan, std::size_t ref_first_scan,
                                     const Eigen::Isometry3d& T_query_ref);

/// T_gt_query_ref = T_world_sensor[query_first]^-1 * T_world_sensor[ref_first]: the map frames are the
/// frames of the maps' first scans, as in MapClosureForEval. `gt_scan_pairs` may be in any order.
MapMetrics EvaluateMapClosures(const std::vector<MapClosureForEval>& closures, const Poses& T_world_sensor,
                               const std::vector<ScanPair>& gt_scan_pairs, const MapMetricsConfig& config);

/// The scans of one local map, as the mapper cut them.
struct MapRange {
    std::size_t first_scan = 0;
    std::size_t last_scan = 0;  ///< inclusive
};

/// Index of the map holding `scan` (`maps` sorted by first scan, disjoint), or maps.size() when none does.
std::size_t MapIndexOfScan(const std::vector<MapRange>& maps, std::size_t scan);

struct MapRecall {
    std::size_t maps_with_revisit = 0;  ///< query maps with ground-truth scan pairs to some earlier map
    std::size_t maps_found_right = 0;   ///< of those, maps with an accepted closure to a right earlier map
    double recall = 0.0;                ///< found / with revisit (0 when no map revisits)
};

/// Map-level recall: did each map that truly revisits an earlier one get a right closure? `maps` sorted
/// by first scan with disjoint ranges; a closure's query map is the one whose first scan it names.
MapRecall ComputeMapRecall(const std::vector<MapRange>& maps, const std::vector<MapClosureForEval>& closures,
                           const std::vector<ScanPair>& gt_scan_pairs, const MapMetricsConfig& config);

/// Yaw of a rotation [rad] in (-pi, pi], from its rotated x axis.
double YawOf(const Eigen::Isometry3d& T);

}  // namespace revisit
