#pragma once
/// The exports every run folder gets (pose_graph.g2o, closures.json, occupancy.png + .yaml), and
/// `revisit export` for finished runs.
#include <filesystem>
#include <string>
#include <vector>

#include "config/config.hpp"
#include "exports/run_occupancy.hpp"
#include "runfolder/run_folder.hpp"
#include "runfolder/run_state.hpp"

namespace revisit {

/// pose_graph.g2o (per map), closures.json and occupancy.png + occupancy.yaml into the run folder.
void WriteRunExports(const RunFolder& run, const RunState& state, const PipelineConfig& config,
                     const OccupancyProgress& on_occupancy_map = {});

struct ExportOptions {
    std::string format = "g2o";  ///< "g2o", "closures-json" or "occupancy"
    bool per_scan = false;       ///< g2o: one vertex per scan instead of per local map
    /// `key=value` over the run's config.yaml: occupancy.* keys only (the graph and closures are the run's).
    std::vector<std::string> overrides;
    std::filesystem::path out;   ///< empty: into the run folder (pose_graph.g2o, pose_graph_scans.g2o, closures.json, occupancy.png)
    OccupancyProgress on_occupancy_map;  ///< occupancy: after each map of each pass (empty: none)
};

/// Re-creates an export from a finished run folder; returns the file written (occupancy: its YAML). Throws ConfigError for an
/// unknown format and DatasetError for a damaged run folder.
std::filesystem::path ExportRun(const std::filesystem::path& run_folder, const ExportOptions& options);

}  // namespace revisit
