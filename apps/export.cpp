/// `revisit export RUN --format g2o|closures-json|occupancy`: a finished run's results for other tools.
#include <iostream>
#include <functional>

#include "commands.hpp"
#include "exports/run_exports.hpp"
#include "pipeline/progress.hpp"

namespace revisit::app {
namespace {

struct ExportCommandOptions {
    std::string run;
    ExportOptions export_options;
    std::string out;
    bool quiet = false;
};

}  // namespace

void AddExportCommand(CLI::App& root, Action& action) {
    auto o = std::make_shared<ExportCommandOptions>();
    auto* cmd = root.add_subcommand("export", "Write a finished run's pose graph (g2o), closures (JSON) or occupancy grid (PNG or PGM + YAML) for other tools");
    cmd->footer(
        "Every run folder already holds pose_graph.g2o (one vertex per local map), closures.json and occupancy.png +\n"
        "occupancy.yaml (map_server / nav2); this command writes them again from the run folder, the graph also per\n"
        "scan, the grid with other --set occupancy.* values (docs/formats.md describes all three).\n"
        "Examples:\n"
        "  revisit export runs/kitti00 --format g2o --per-scan      (runs/kitti00/pose_graph_scans.g2o)\n"
        "  revisit export runs/intel --format closures-json --out intel_closures.json\n"
        "  revisit export runs/intel --format occupancy --set occupancy.resolution=0.1 --out intel_10cm.pgm");
    cmd->add_option("run", o->run, "run folder")->required();
    cmd->add_option("--format", o->export_options.format, "g2o, closures-json or occupancy")->capture_default_str();
    cmd->add_flag("--per-scan", o->export_options.per_scan, "g2o: one vertex per scan instead of per local map");
    cmd->add_option("--out", o->out, "file to write (default: into the run folder; occupancy: the .png or .pgm, its .yaml beside it)");
    cmd->add_option("--set", o->export_options.overrides, "occupancy: key=value over the run's config.yaml (occupancy.* keys)");
    cmd->add_flag("--quiet", o->quiet, "no progress output");
    cmd->callback([o, &action] {
        action = [o] {
            o->export_options.out = o->out;
            // The grid reads every local map twice: a minute on a 100,000-scan run.
            CountedProgress progress(std::cerr, Progress::DetectMode(o->quiet), "map passes (occupancy grid)");
            o->export_options.on_occupancy_map = std::ref(progress);
            std::cout << ExportRun(o->run, o->export_options).string() << '\n';
            return 0;
        };
    });
}

}  // namespace revisit::app
