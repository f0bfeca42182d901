#pragma once
/// `revisit bench`: the suites (lists of cases) over every stage and the whole chain (issue 10).
#include <filesystem>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "bench_suite/data_dir.hpp"
#include "bench_suite/record.hpp"

namespace revisit {

/// How big a suite's cases are. "quick" < 3 min on 2 cores; "full" adds sizes and repetitions;
/// "tiny" is for tests (seconds).
struct SuiteScale {
    MeasureConfig repeat;                         ///< warm-up and repetitions of every figure
    std::size_t odometry_scans = 20;              ///< scans per odometry run
    std::size_t odometry_skip = 100;              ///< simulated scans skipped first (the start is slow)
    std::size_t map_scans = 60;                   ///< simulated 64-beam scans for the local-map cases
    std::vector<int> database_sizes;              ///< tree query+insert curve [maps]
    int tree_queries = 20;                        ///< timed query+insert per database size
    std::vector<int> fleet_database_sizes;        ///< fleet_tree: maps of many sessions over many places
    std::vector<std::pair<int, int>> graph_grid;  ///< pose graph (nodes, closures)
    int consistency_maps = 1000;                  ///< maps of the online closure-consistency case
    std::size_t gt_scans = 300;                   ///< scans of the ground-truth closure case
    std::vector<std::size_t> scan_context_scans;  ///< sequence lengths of the ScanContext search case [scans]
    int report_closures = 5;                      ///< closure pages rendered
    std::size_t end_to_end_scans = 150;           ///< 64-beam city scans through `revisit run`; 0: the whole route
    int end_to_end_repetitions = 1;               ///< runs of the whole chain (no warm-up)
};

/// The scale of a suite name; throws ConfigError for an unknown name.
SuiteScale ScaleOf(const std::string& suite);
std::vector<std::string> SuiteNames();

struct BenchOptions {
    std::string suite = "quick";
    std::filesystem::path data_dir;                    ///< real data (kitti00_first16, radish); "" or absent: skipped
    std::filesystem::path scratch_dir;                 ///< temporary files; "" = a fresh folder under the system temp
    std::vector<std::string> groups;                   ///< only these case groups (empty: all), see CaseGroupNames()
    std::function<void(const std::string&)> progress;  ///< told the name of each case before it runs
};

/// Case groups in run order: reader, odometry, local_map, closures, tree, refinement, pose_graph,
/// ground_truth, report, end_to_end.
std::vector<std::string> CaseGroupNames();

/// Runs the suite (respects the caller's tbb::global_control; the 1-thread figures cap it at 1).
BenchRecord RunSuite(const BenchOptions& options);

}  // namespace revisit
