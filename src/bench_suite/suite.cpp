#include "bench_suite/suite.hpp"

#include <stdlib.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <chrono>
#include <random>

#include "bench_suite/cases.hpp"
#include "core/error.hpp"

namespace revisit {

namespace {
struct CaseGroup {
    const char* name;
    void (*run)(const CaseContext&);
};

/// Run order: end_to_end first so that the peak memory it reports is the pipeline's, not the fixtures'.
const CaseGroup kGroups[] = {
    {"end_to_end", EndToEndCases},   {"reader", ReaderCases},         {"bag_reader", BagReaderCases},
    {"odometry", OdometryCases},
    {"local_map", LocalMapCases},    {"closures", ClosureStageCases}, {"tree", TreeCases},
    {"fleet_tree", FleetTreeCases},
    {"refinement", RefinementCases}, {"pose_graph", PoseGraphCases},  {"ground_truth", GroundTruthCases},
    {"scan_context", ScanContextCases},
    {"consistency", ConsistencyCases}, {"proximity", ProximityCases}, {"report", ReportCases},
};

/// A new folder of its own in the temporary folder, created exclusively (mkdtemp): a folder or link
/// planted under a guessed name is never written into, and removing it removes only the suite's files.
std::filesystem::path FreshScratch() {
    std::string pattern = (std::filesystem::temp_directory_path() / "revisit-bench-XXXXXX").string();
    if (::mkdtemp(pattern.data()) == nullptr) {
        throw DatasetError(pattern, std::string("cannot create a scratch folder: ") + std::strerror(errno));
    }
    return pattern;
}
}  // namespace

std::vector<std::string> SuiteNames() { return {"tiny", "quick", "full"}; }

SuiteScale ScaleOf(const std::string& suite) {
    SuiteScale s;
    if (suite == "tiny") {
        s.repeat = {0, 2};
        s.odometry_scans = 3;
        s.odometry_skip = 5;
        s.map_scans = 8;
        s.database_sizes = {10, 30};
        s.fleet_database_sizes = {80};
        s.tree_queries = 3;
        s.graph_grid = {{300, 10}};
        s.consistency_maps = 100;
        s.gt_scans = 60;
        s.scan_context_scans = {500, 2000};
        s.report_closures = 1;
        s.end_to_end_scans = 12;
    } else if (suite == "quick") {
        s.repeat = {1, 5};
        s.odometry_scans = 50;
        s.map_scans = 60;
        s.database_sizes = {10, 100, 1000, 5000};
        s.fleet_database_sizes = {1000, 5000};
        s.tree_queries = 20;
        s.graph_grid = {{500, 50}, {2000, 200}};
        s.gt_scans = 600;
        s.scan_context_scans = {5000, 20000};
        s.report_closures = 3;
        s.end_to_end_scans = 300;
    } else if (suite == "full") {
        s.repeat = {1, 9};
        s.odometry_scans = 50;
        s.map_scans = 90;
        s.database_sizes = {10, 100, 1000, 5000, 10000, 20000, 50000};
        s.fleet_database_sizes = {10000, 50000, 100000};
        s.tree_queries = 30;
        s.graph_grid = {{500, 50}, {2000, 50}, {2000, 200}, {2000, 1000}, {10000, 200}, {10000, 1000}};
        s.gt_scans = 2000;
        s.scan_context_scans = {10000, 40000, 100000};
        s.report_closures = 10;
        s.end_to_end_scans = 0;  // the whole ~3 km route with its revisits
        s.end_to_end_repetitions = 2;
    } else {
        throw ConfigError("bench: unknown suite '" + suite + "' (known: tiny, quick, full)");
    }
    return s;
}

std::vector<std::string> CaseGroupNames() {
    std::vector<std::string> names;
    for (const auto& g : kGroups) names.push_back(g.name);
    return names;
}

BenchRecord RunSuite(const BenchOptions& options) {
    const auto start = std::chrono::steady_clock::now();
    for (const auto& g : options.groups) {
        const auto names = CaseGroupNames();
        if (std::find(names.begin(), names.end(), g) == names.end())
            throw ConfigError("bench: unknown case group '" + g + "'");
    }
    BenchRecord record;
    record.suite = options.suite;
    record.started_utc = UtcNow();
    record.machine = CurrentMachine();
    FixtureCache fixtures;
    CaseContext context;
    context.scale = ScaleOf(options.suite);
    if (!options.data_dir.empty() && std::filesystem::exists(options.data_dir))
        context.data_dir = options.data_dir;
    else
        record.skipped.push_back("real-data cases: " + (options.data_dir.empty()
                                                            ? std::string("no --data")
                                                            : options.data_dir.string() + " absent"));
    record.data_dir = context.data_dir.string();
    const bool own_scratch = options.scratch_dir.empty();
    context.scratch_dir = own_scratch ? FreshScratch() : options.scratch_dir;
    std::filesystem::create_directories(context.scratch_dir);
    context.fixtures = &fixtures;
    context.out = &record.results;
    context.skipped = &record.skipped;
    try {
        for (const auto& group : kGroups) {
            if (!options.groups.empty() &&
                std::find(options.groups.begin(), options.groups.end(), group.name) == options.groups.end())
                continue;
            if (options.progress) options.progress(group.name);
            group.run(context);
        }
    } catch (...) {
        if (own_scratch) std::filesystem::remove_all(context.scratch_dir);
        throw;
    }
    if (own_scratch) std::filesystem::remove_all(context.scratch_dir);
    record.duration_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    record.peak_memory_kb = PeakMemoryKb();
    return record;
}

}  // namespace revisit
