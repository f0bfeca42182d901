#pragma once
/// Scan-level closures predicted by map-level closures (METHOD.md section 7, "Predicted closures"
/// steps 1-2; thesis section 5.1, Fig. 5.1).
#include "core/trajectory.hpp"
#include "evaluation/map_closure.hpp"
#include "evaluation/scan_pair.hpp"

#include <vector>

namespace revisit {

struct PredictedClosureConfig {
    double max_distance = 0.0;  ///< tau_d [m]: scan pairs closer than this after the correction are closures;
                                ///< 0 in a run's config: OverlapDistance of its ground truth (the paper's is 6)
    bool planar = false;        ///< measure the distance in x, y only (2D sensors, or maps levelled in z)
};

/// For each map closure: the odometry poses of both maps' scans relative to each map's first scan,
/// the reference map's scans moved by T_query_ref, and every (reference, query) scan pair closer than
/// tau_d, scored by the closure's inliers. `T_odom_sensor` holds one odometry pose per scan.
/// Pairs may repeat across closures; the sweep keeps the best score of each.
std::vector<ScoredPair> ExpandMapClosures(const std::vector<MapClosureForEval>& closures, const Poses& T_odom_sensor,
                                          const PredictedClosureConfig& config);

/// The ground-truth scan pairs whose reference positions lie closer than tau_d: the most a map-level
/// method can predict under this protocol, even with perfect alignments (the overlap criterion of the
/// ground truth admits pairs farther apart). Their share of `ground_truth` bounds the recall.
std::size_t CountPairsWithinTau(const std::vector<ScanPair>& ground_truth, const Poses& T_world_sensor,
                                const PredictedClosureConfig& config);

}  // namespace revisit
