#pragma once
/// Every parameter of a run, grouped by stage, with the one schema that reads and writes them as
/// YAML (configs/default.yaml documents each with its unit and source).
#include <set>
#include <string>
#include <vector>

#include "closures/detector.hpp"
#include "closures/local_map.hpp"
#include "evaluation/closure_truth.hpp"
#include "evaluation/ground_truth_closures.hpp"
#include "evaluation/predicted_closures.hpp"
#include "evaluation/scan_context.hpp"
#include "io/reader.hpp"
#include "odometry/odometry_config.hpp"
#include "optimization/closure_consistency.hpp"
#include "optimization/pose_graph.hpp"
#include "optimization/refinement.hpp"
#include "config/config_schema.hpp"

namespace revisit {

struct InputConfig {
    /// Derive the settings no file or --set gave from the first scans (src/settings/auto_settings.hpp).
    bool auto_settings = true;
    /// With auto_settings and no given odometry.max_range: the crop radius follows the scene's scale as
    /// the sequence unfolds (src/settings/scene_scale_watch.hpp).
    bool follow_scene_scale = true;
    bool kitti_vertical_correction = false;  ///< KITTI HDL-64E: rotate points by 0.205 deg (configs/kitti.yaml)
    std::string sensor_label;                ///< rawlogs: only this sensor ("" = all)
    double laser_aperture_deg = 0.0;         ///< [deg] 2D lasers: replaces the file's aperture (0: keep)
    /// ROS bags: the scan topic (PointCloud2 or LaserScan), the odometry prior (Odometry) and the
    /// reference poses (PoseStamped, Path or Odometry); "" = the only topic of a fitting type, "none" = none.
    std::string topic;
    std::string odometry_topic;
    std::string reference_topic;
    double reference_end_tolerance = 0.0;    ///< [s] TUM poses: how far past their ends a scan takes the end pose (0: half their median spacing)
    double reference_max_gap = 0.0;          ///< [s] TUM poses: longest gap interpolated across (0: 5 x their median spacing)
};

struct GraphNoiseConfig {
    double odometry_translation_per_m = 0.01;  ///< [m/m] odometry edge sigma per metre between map origins (1%)
    double odometry_rotation_per_m = 3e-4;     ///< [rad/m] (~1.7 deg per 100 m)
    bool closure_information_from_registration = false;  ///< else a fixed closure sigma below
    double closure_sigma_translation = 0.03;  ///< [m] ~ 1e3 x identity information (paper)
    double closure_sigma_rotation = 0.03;     ///< [rad]
    int optimize_every_closures = 1;          ///< online: re-optimize after this many accepted closures (or a tenth of the graph's)
    double online_time_budget = 0.2;          ///< [s] per online update (the final batch has none)
    /// After the final optimization, verified closures whose robust weight fell below this are reported
    /// as rejected: the graph found them inconsistent with the odometry and the other closures.
    double min_weight = 0.1;
};

/// The proximity pass (docs/method.md, "At the end of the run"): after the final optimization, maps
/// that the corrected poses lay over each other are registered directly from that estimate, verified
/// like any closure, and join the graph when they agree with every accepted closure.
struct ProximityConfig {
    bool enabled = true;
    int rounds = 2;             ///< passes, each from the estimate the previous one improved
    /// Predicted overlap (shared ground cells / cells of the smaller map, cells of 1/20 of a map's
    /// length) from which a pair is registered.
    double min_overlap = 0.3;
    int max_per_map = 3;        ///< registrations per map and round, largest predicted overlap first (cost bound)
    /// With fewer consistent detector closures than this, the pass first registers the maps the odometry
    /// itself lays over each other, and those closures may displace the detector's (docs/method.md: the odometry's
    /// own overlays); 0: never.
    int odometry_check_below = 3;
    /// Two maps of one session that are not consecutive are registered only when the path between their
    /// first scans is at least this many times the straight line between them, or when their scans meet
    /// (within a tenth of a map's length, a map's length of travel apart): the platform came back. A
    /// sensor that sees farther than a map is long overlays maps a few apart along a path that never
    /// returned; registering them measures what the odometry between them already does, less precisely
    /// (docs/method.md). 0: every pair the estimate overlays.
    double revisit_detour = 2.0;
};

struct OutputConfig {
    double map_voxel = 0.5;      ///< [m] downsampling of each local map stored in the run folder
    double global_map_voxel = 0.5;  ///< [m] downsampling of the corrected global map (PLY)
    /// A corrected global map past this many points doubles global_map_voxel until it fits (run.json:
    /// setting_updates): 2 M points are a 24 MB PLY and ~0.15 GB to build, however long the drive.
    /// 0: no cap. A global_map_voxel given explicitly is kept as it is.
    int global_map_max_points = 2000000;
    bool write_report = true;    ///< render report/index.html at the end
    /// Report pages for this many of the strongest candidates below the acceptance threshold, besides every
    /// closure that reached it; the others are rows of the index's table (`revisit inspect` renders them).
    int report_candidates = 8;
    /// Of the closures that reached the acceptance threshold, pages for at most this many (the worst, the
    /// best, an even sample); every accepted closure the reference calls false has one besides. The report's
    /// size then does not grow with the sequence: the others are table rows (`revisit inspect`).
    int report_closure_pages = 20;
    int report_map_pages = 30;  ///< at most this many map pages (the maps of the closures at the threshold first)
    bool scan_context = true;    ///< also run the ScanContext baseline when ground truth exists
    bool elevation_ablation = true;  ///< also score the elevation-image ablation when ground truth exists
};

/// The occupancy grid every run writes (occupancy.png, occupancy.yaml: src/exports/run_occupancy.hpp).
struct OccupancyConfig {
    double resolution = 0.0;          ///< [m per cell]; 0: 0.05 for 2D lasers, the stored maps' voxel for 3D runs
    /// A larger extent doubles the cell until it fits (occupancy.yaml says which): the grid then holds at
    /// most 16.8 M cells (67 MB of counts, a 17 MB image) however long the drive.
    int max_cells_per_side = 4096;
    /// A cell observed this often as a ray's end, of all rays that ended in or crossed it, is occupied;
    /// below, it is free. Walls seen at a grazing angle are also crossed by their neighbours' rays.
    double occupied_share = 0.25;
    double min_height = 0.3;          ///< [m] 3D runs: lowest obstacle above the levelled ground
    double max_height = 2.0;          ///< [m] 3D runs: highest (a vehicle's or a person's height)
    double ground_tolerance = 0.25;   ///< [m] 3D runs: points this close to the ground make a cell free
    /// [m] 3D runs: the ground under a point is the lowest point within one such cell of its own (at least
    /// the stored maps' voxel): it follows slopes and terraces that one plane per map does not.
    double ground_cell = 0.5;
};

/// Several sessions and many machines (issue 20): `revisit merge`, `run --against`, `revisit batch`.
struct FleetConfig {
    /// Two sessions are joined only by at least this many mutually consistent cross-session closures
    /// (1 trusts a lone verified closure, which nothing else can check).
    int min_cross_closures = 1;
    int slurm_cpus_per_task = 2;     ///< `revisit batch --engine slurm`: --cpus-per-task of each run
    int slurm_memory_mb = 4096;      ///< [MiB] --mem of each run and of the merge
    int slurm_time_minutes = 120;    ///< [min] --time of each run and of the merge
    std::string slurm_partition;     ///< --partition ("": the cluster's default)
};

/// The pose graph's defaults for the pipeline: graduated robustness on, because closures arrive far
/// from drifted odometry (measured on the simulated demo city: APE 56.8 m -> 49.7 m without, 20.7 m
/// with, the same 17 correct closures).
inline PoseGraphConfig PipelineGraphConfig() {
    PoseGraphConfig config;
    config.anneal = true;
    return config;
}

struct PipelineConfig {
    InputConfig input;
    OdometryConfig odometry;
    LocalMapConfig local_map;
    ClosureDetectorConfig detector;
    RefinementConfig refinement;
    PoseGraphConfig graph = PipelineGraphConfig();
    GraphNoiseConfig graph_noise;
    ClosureConsistencyConfig consistency;
    ProximityConfig proximity;
    GtClosureConfig ground_truth;
    ClosureTruthConfig truth;
    PredictedClosureConfig predicted;
    ScanContextConfig scan_context;
    OutputConfig output;
    OccupancyConfig occupancy;
    FleetConfig fleet;
    /// Keys a config file or --set gave a value (LoadConfig fills it): automatic settings leave them alone.
    std::set<std::string> explicit_keys;
    /// Settings derived from the data and why (src/settings/auto_settings.hpp), for config.yaml and run.json.
    std::vector<std::string> derived;
};

/// output.global_map_max_points, or 0 (no cap) when output.global_map_voxel was given: an explicit voxel wins.
inline std::size_t GlobalMapMaxPoints(const PipelineConfig& config) {
    return config.explicit_keys.count("output.global_map_voxel") != 0 ? 0 : std::size_t(config.output.global_map_max_points);
}

/// The schema bound to `config`'s fields (`config` must outlive it).
ConfigSchema MakeConfigSchema(PipelineConfig& config);

/// Defaults, then each file in order, then `key=value` overrides. Throws ConfigError.
PipelineConfig LoadConfig(const std::vector<std::string>& files, const std::vector<std::string>& overrides);

/// Reader options from the input section.
ReaderOptions MakeReaderOptions(const InputConfig& input);

/// The fully resolved configuration as commented YAML (what a run writes to config.yaml).
std::string DumpConfig(const PipelineConfig& config);

}  // namespace revisit
