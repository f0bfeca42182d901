#pragma once
/// A synthetic run (loop route through a world of boxes, drifting odometry, N closures with matches) for the
/// report's tests and benchmark, and for trying the report without data.
#include "report/report_input.hpp"

#include <cstdint>

namespace revisit {

struct SyntheticRunConfig {
    int num_closures = 10;          ///< one per revisited local map
    int maps_per_lap = 10;          ///< local maps along one lap of the loop
    int scans_per_map = 20;
    double loop_radius = 60.0;      ///< [m]
    double map_radius = 40.0;       ///< [m] world points within this distance of a map's origin
    double yaw_drift = 0.1;         ///< [rad per lap] odometry heading drift
    double reject_fraction = 0.2;   ///< closures marked rejected
    /// Extra candidates below the acceptance threshold (3-9 inliers between random maps, wrong poses), as a long
    /// real sequence produces by the thousand.
    int weak_candidates = 0;
    /// Accepted closures of the proximity pass (registered at the true pose, no image matches), after the others,
    /// between maps of the second lap and the last maps of the first.
    int proximity_closures = 0;
    std::uint32_t seed = 1;
};

/// Builds a complete ReportInput; its callbacks compute maps and density images on demand (thread-safe).
ReportInput MakeSyntheticRun(const SyntheticRunConfig& config = {});

}  // namespace revisit
