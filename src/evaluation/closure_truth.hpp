#pragma once
/// Truth of accepted closures where reference poses exist, and revisit coverage: "were my revisits
/// found?" (issue 16). A closure is true when its relative pose agrees with the reference relative pose
/// of the two maps' first scans (ClosureErrorAgainst).
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
    ClosurePoseError error;
};

struct ClosureTruth {
    std::vector<ClosureVerdict> verdicts;  ///< one per input closure
    std::size_t num_true = 0;
    std::size_t num_false = 0;
};

/// Judges each closure (its T_query_ref against the reference poses of the maps' first scans).
ClosureTruth JudgeClosures(const std::vector<MapClosureForEval>& closures, const Poses& T_world_reference,
                           const ClosureTruthConfig& config);

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
