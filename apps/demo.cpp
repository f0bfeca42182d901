/// `revisit demo`: the simulator's drive read as a dataset (sim:PRESET), the whole chain, the report.
#include <iostream>

#include "commands.hpp"
#include "pipeline/progress.hpp"
#include "pipeline/run_and_report.hpp"
#include "run_options.hpp"
#include "sim/sim_reader.hpp"

namespace revisit::app {
namespace fs = std::filesystem;
namespace {
struct DemoOptions {
    std::string preset = "demo";
    std::string out;
    ConfigOptions config;
    bool quiet = false;
};

int RunDemo(const DemoOptions& o) {
    const auto threads = LimitThreads(o.config.threads);
    // The simulator is read as a dataset: each scan is ray-cast as the chain asks for it, nothing is
    // cached, and the evaluation reads the same scans again the same way (sim/sim_reader.hpp).
    const fs::path data = "sim:" + o.preset;
    SimConfigFromSpec(data.string());  // an unknown preset fails here, before any work
    std::cerr << "revisit demo: simulating the '" << o.preset << "' drive as it is read (" << data.string() << ")\n";
    const PipelineConfig config = ResolveConfigFor(o.config, data, std::cerr);
    RunOptions run_options;
    run_options.dataset = data;
    run_options.quiet = o.quiet;
    run_options.out = o.out.empty() ? RunFolder::DefaultPath("reports", "demo") : fs::path(o.out);
    run_options.force = !o.out.empty();
    const RunState state = RunAndReport(run_options, config, std::cerr, std::cout);
    if (o.out.empty()) RunFolder::UpdateLatestLink(run_options.out);
    return state.complete ? 0 : 130;
}
}  // namespace

void AddDemoCommand(CLI::App& root, Action& action) {
    auto o = std::make_shared<DemoOptions>();
    auto* cmd = root.add_subcommand("demo", "Simulate a city drive with revisits and run the whole chain on it");
    cmd->footer(
        "Reads the simulator's drive as a dataset (sim:PRESET): each scan is ray-cast as it is read, so\n"
        "nothing but the run folder is written. Then: odometry, closures, pose graph, evaluation against\n"
        "the simulator's ground truth, report. Settings follow the data as for any dataset; the same run\n"
        "is `revisit run sim:demo`.\n"
        "Examples:\n"
        "  revisit demo\n"
        "  revisit demo --preset city-livox --config livox");
    cmd->add_option("--preset", o->preset, "simulator preset (revisit simulate --list-presets)")->capture_default_str();
    cmd->add_option("--out", o->out, "run folder (default: reports/demo-<time>)");
    AddConfigOptions(*cmd, o->config);
    cmd->add_flag("--quiet", o->quiet, "no progress output");
    cmd->callback([o, &action] { action = [o] { return RunDemo(*o); }; });
}

}  // namespace revisit::app
