#pragma once
/// Every parameter of a run, grouped by stage, with the one schema that reads and writes them as
/// YAML (configs/default.yaml documents each with its unit and source).
#include <string>
#include <vector>

#include "closures/detector.hpp"
#include "closures/local_map.hpp"
#include "evaluation/ground_truth_closures.hpp"
#include "evaluation/predicted_closures.hpp"
#include "evaluation/scan_context.hpp"
#include "odometry/odometry_config.hpp"
#include "optimization/pose_graph.hpp"
#include "optimization/refinement.hpp"
#include "pipeline/config_schema.hpp"

namespace revisit {

struct InputConfig {
    bool kitti_vertical_correction = false;  ///< KITTI HDL-64E: rotate points by 0.205 deg (configs/kitti.yaml)
    std::string sensor_label;                ///< rawlogs: only this sensor ("" = all)
};

struct GraphNoiseConfig {
    double odometry_sigma_translation = 0.1;  ///< [m] per odometry edge between map origins
    double odometry_sigma_rotation = 0.01;    ///< [rad]
    bool closure_information_from_registration = false;  ///< else a fixed closure sigma below
    double closure_sigma_translation = 0.03;  ///< [m] ~ 1e3 x identity information (METHOD.md 6)
    double closure_sigma_rotation = 0.03;     ///< [rad]
    int optimize_every_closures = 1;          ///< online: re-optimize after this many accepted closures
    double online_time_budget = 0.2;          ///< [s] per online update (the final batch has none)
};

struct OutputConfig {
    double map_voxel = 0.5;      ///< [m] downsampling of each local map stored in the run folder
    double global_map_voxel = 0.5;  ///< [m] downsampling of the corrected global map (PLY)
    bool write_report = true;    ///< render report/index.html at the end
    bool scan_context = true;    ///< also run the ScanContext baseline when ground truth exists
    bool elevation_ablation = true;  ///< also score the elevation-image ablation when ground truth exists
};

struct PipelineConfig {
    InputConfig input;
    OdometryConfig odometry;
    LocalMapConfig local_map;
    ClosureDetectorConfig detector;
    RefinementConfig refinement;
    PoseGraphConfig graph;
    GraphNoiseConfig graph_noise;
    GtClosureConfig ground_truth;
    PredictedClosureConfig predicted;
    ScanContextConfig scan_context;
    OutputConfig output;
};

/// The schema bound to `config`'s fields (`config` must outlive it).
ConfigSchema MakeConfigSchema(PipelineConfig& config);

/// Defaults, then each file in order, then `key=value` overrides. Throws ConfigError.
PipelineConfig LoadConfig(const std::vector<std::string>& files, const std::vector<std::string>& overrides);

/// The fully resolved configuration as commented YAML (what a run writes to config.yaml).
std::string DumpConfig(const PipelineConfig& config);

}  // namespace revisit
