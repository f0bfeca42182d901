/// `revisit demo`: simulate the default city once (cached), run the whole chain, print the report path.
#include <cstdlib>
#include <fstream>
#include <iostream>

#include "commands.hpp"
#include "core/atomic_file.hpp"
#include "pipeline/progress.hpp"
#include "pipeline/run_and_report.hpp"
#include "run_options.hpp"
#include "sim/presets.hpp"
#include "sim/simulate.hpp"

namespace revisit::app {
namespace fs = std::filesystem;
namespace {
struct DemoOptions {
    std::string preset = "demo";
    std::string out;
    ConfigOptions config;
    bool quiet = false;
};

fs::path CacheFolder(const std::string& preset, std::uint64_t seed) {
    const char* xdg = std::getenv("XDG_CACHE_HOME");
    const char* home = std::getenv("HOME");
    const fs::path base = xdg && *xdg ? fs::path(xdg) : home && *home ? fs::path(home) / ".cache" : fs::temp_directory_path();
    // "v2": the worlds of issue 15 (rough ground, foliage, clutter, sensor residuals); an older cache is not reused.
    return base / "revisit" / ("sim-v2-" + preset + "-seed" + std::to_string(seed));
}

int RunDemo(const DemoOptions& o) {
    const auto threads = LimitThreads(o.config.threads);
    const SimConfig sim = SimPreset(o.preset);
    const fs::path data = CacheFolder(o.preset, sim.seed);
    const fs::path done_marker = data / ".complete";
    if (!fs::exists(done_marker)) {
        std::cerr << "revisit demo: simulating the '" << o.preset << "' sequence into " << data.string() << " (once)\n";
        std::optional<Progress> progress;
        RunSimulation(sim, data, true, [&](std::size_t done, std::size_t total) {
            if (!progress) progress.emplace(std::cerr, Progress::DetectMode(o.quiet), total);
            progress->Update(done);
        });
        WriteFileAtomically(done_marker, std::string_view("ok\n"));
    } else {
        std::cerr << "revisit demo: using the cached sequence " << data.string() << '\n';
    }
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
        "The first run simulates the sequence into ~/.cache/revisit (about a minute); later runs reuse it.\n"
        "Then: odometry, closures, pose graph, evaluation against the simulator's ground truth, report.\n"
        "Without --config it uses the 'sim' preset (finer odometry voxels for simulated worlds).\n"
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
