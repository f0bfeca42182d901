#pragma once
/// Everything a run computes, small enough to keep for a whole sequence (poses, map and closure
/// records; never the scans or map points), and what `revisit eval` / `revisit report` read back.
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "closures/closure.hpp"
#include "closures/detector.hpp"
#include "core/trajectory.hpp"
#include "optimization/refinement.hpp"

namespace revisit {

struct MapRecordSummary {
    int id = 0;
    std::size_t first_scan = 0;
    std::size_t last_scan = 0;  ///< inclusive
    Eigen::Isometry3d T_world_map = Eigen::Isometry3d::Identity();  ///< odometry pose of the first scan
    Eigen::Isometry3d T_world_map_corrected = Eigen::Isometry3d::Identity();
    double travel_start = 0.0;  ///< [m]
    double travel_end = 0.0;    ///< [m]
    std::size_t num_points = 0;
    int num_keypoints = 0;
    Eigen::Vector2d density_origin = Eigen::Vector2d::Zero();  ///< [m]
    double density_resolution = 0.0;                           ///< [m per pixel]
    Eigen::Isometry3d T_ground_map = Eigen::Isometry3d::Identity();
};

struct ClosureRecord {
    /// "density" (the detector), "proximity" (registered because the corrected poses lay the two maps
    /// over each other) or "elevation" (the ablation, never used in the graph).
    std::string method = "density";
    Closure closure;
    RefinementResult refinement;
    bool refined = false;            ///< false: below the acceptance threshold, not refined
    bool accepted = false;           ///< verified (refinement.accepted), and its final graph weight >= graph.min_weight
    std::string reason;              ///< why not accepted
    double graph_weight = 0.0;       ///< final robust weight in the pose graph (verified closures only)
};

/// A setting changed mid-run because the data changed ("updated as the sequence unfolds").
struct SettingUpdate {
    std::size_t scan = 0;  ///< position of the first scan processed with the new value
    std::string key;       ///< e.g. "odometry.max_range"
    double from = 0.0;
    double to = 0.0;
    std::string reason;
};

/// Accumulated wall time per stage.
struct StageTimer {
    double total_ms = 0.0;
    std::size_t count = 0;
};

/// The closure is one the pose graph may use: the detector's or the proximity pass's.
inline bool CorrectsTrajectory(const ClosureRecord& record) { return record.method == "density" || record.method == "proximity"; }

struct RunState {
    std::string dataset;
    std::string format;
    std::string poses_source;  ///< "odometry", "dataset" or a file
    bool complete = false;     ///< false when interrupted
    std::string truncated;     ///< --allow-truncated: why reading stopped early (empty: the input was read whole)
    std::vector<double> timestamps;
    Poses odometry;            ///< per scan: the poses the maps were built from
    Poses corrected;           ///< per scan, after the pose graph
    Poses reference;           ///< per scan, or empty when the dataset has no reference; see reference_scans
    /// When the reference covers only some scans (a TUM reference paired by time: scans outside its
    /// span or in a gap have none): the positions of those it covers, sorted, one per `reference`
    /// pose. Empty when it covers every scan (or none).
    std::vector<std::size_t> reference_scans;
    std::vector<int> map_of_scan;
    /// Scans (positions in `odometry`) whose pose is only the motion prediction: the odometry found the
    /// scan degenerate or its registration diverged (issue 14: divergence is reported, never hidden).
    std::vector<std::size_t> odometry_fallbacks;
    std::vector<SettingUpdate> setting_updates;  ///< settings that followed the data mid-run
    std::vector<MapRecordSummary> maps;
    std::vector<ClosureRecord> closures;
    std::vector<MapComparison> comparisons;  ///< the density detector's skipped, voted-for and compared pairs
    std::map<std::string, StageTimer> timings;
    double wall_seconds = 0.0;
    std::size_t peak_rss_kb = 0;

    /// A reference pose for every scan: what the report's reference pictures and the sessions need.
    bool has_reference() const { return !reference.empty() && reference.size() == odometry.size() && reference_scans.empty(); }
    /// A reference for some scans only (reference_scans): the trajectory metrics use those, the closure
    /// metrics the local maps it covers whole (pipeline/covered_run.hpp).
    bool has_partial_reference() const { return !reference_scans.empty() && reference_scans.size() == reference.size(); }
    /// Closures in the final pose graph (the detector's and the proximity pass's).
    std::size_t NumAccepted() const;
};

/// The map (index into `maps`, sorted by first scan, contiguous ranges) of every scan; -1 without maps.
std::vector<int> MapOfScan(const std::vector<MapRecordSummary>& maps, std::size_t num_scans);

}  // namespace revisit
