/// `revisit export RUN --format g2o|closures-json`: a finished run's results for other tools.
#include <iostream>

#include "commands.hpp"
#include "exports/run_exports.hpp"

namespace revisit::app {
namespace {

struct ExportCommandOptions {
    std::string run;
    ExportOptions export_options;
    std::string out;
};

}  // namespace

void AddExportCommand(CLI::App& root, Action& action) {
    auto o = std::make_shared<ExportCommandOptions>();
    auto* cmd = root.add_subcommand("export", "Write a finished run's pose graph (g2o) or closures (JSON) for other tools");
    cmd->footer(
        "Every run folder already holds pose_graph.g2o (one vertex per local map) and closures.json; this command\n"
        "writes them again from the run folder, or per scan (docs/formats.md describes both).\n"
        "Examples:\n"
        "  revisit export runs/kitti00 --format g2o --per-scan      (runs/kitti00/pose_graph_scans.g2o)\n"
        "  revisit export runs/intel --format closures-json --out intel_closures.json");
    cmd->add_option("run", o->run, "run folder")->required();
    cmd->add_option("--format", o->export_options.format, "g2o or closures-json")->capture_default_str();
    cmd->add_flag("--per-scan", o->export_options.per_scan, "g2o: one vertex per scan instead of per local map");
    cmd->add_option("--out", o->out, "file to write (default: into the run folder)");
    cmd->callback([o, &action] {
        action = [o] {
            o->export_options.out = o->out;
            std::cout << ExportRun(o->run, o->export_options).string() << '\n';
            return 0;
        };
    });
}

}  // namespace revisit::app
