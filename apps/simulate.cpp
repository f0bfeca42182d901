/// `revisit simulate --preset NAME --out DIR`: a synthetic, ground-truthed sequence.
#include <iostream>

#include "commands.hpp"
#include "pipeline/progress.hpp"
#include "sim/presets.hpp"
#include "sim/simulate.hpp"

namespace revisit::app {
namespace {
struct SimulateOptions {
    std::string preset = "demo";
    std::string out;
    std::uint64_t seed = 0;
    std::size_t max_scans = 0;
    std::string trajectory;
    int session = 0;
    bool force = false;
    bool quiet = false;
    bool list = false;
};

int RunSimulate(const SimulateOptions& options) {
    if (options.list) {
        for (const auto& name : SimPresetNames()) std::cout << name << '\n';
        return 0;
    }
    if (options.out.empty()) throw std::runtime_error("simulate: --out DIR is required (or --list-presets)");
    SimConfig config = SimPreset(options.preset);
    if (options.seed != 0) config.seed = options.seed;
    if (options.max_scans != 0) config.max_scans = options.max_scans;
    config.session = options.session;
    if (!options.trajectory.empty()) {
        // A street world built along the given route, with the preset's sensor and city densities.
        config.world = WorldKind::kAroundTrajectory;
        config.trajectory_file = options.trajectory;
        config.around.city = config.city;
    }
    std::optional<Progress> progress;
    const auto summary = RunSimulation(config, options.out, options.force, [&](std::size_t done, std::size_t total) {
        if (!progress) progress.emplace(std::cerr, Progress::DetectMode(options.quiet), total);
        progress->Update(done);
    });
    if (progress) progress->Finish(summary.scans);
    std::cout << "wrote " << summary.scans << " scans (" << summary.points << " points, " << summary.length
              << " m, " << summary.revisits << " revisits, " << summary.opposite_revisits << " opposite) to "
              << options.out << '\n';
    return 0;
}
}  // namespace

void AddSimulateCommand(CLI::App& root, Action& action) {
    auto options = std::make_shared<SimulateOptions>();
    auto* cmd = root.add_subcommand("simulate", "Write a synthetic sequence with ground truth and revisits");
    cmd->footer(
        "Worlds (city, highway, campus, indoor), routes with revisits and sensor models, deterministic\n"
        "from the seed. OUT is a KITTI folder (velodyne/*.bin, poses.txt ground truth in the sensor frame,\n"
        "times.txt, identity calib.txt, sim.yaml with every parameter) or, ending in .rawlog/.rawlog.gz,\n"
        "an MRPT rawlog with ground truth and a drifting odometry prior.\n"
        "Examples:\n"
        "  revisit simulate --preset demo --out data/demo\n"
        "  revisit simulate --preset indoor-2d-360 --out indoor.rawlog.gz --seed 7\n"
        "  revisit simulate --preset city-64 --trajectory ../shared/data/kitti_gt_poses/00.txt --out sim00\n"
        "  revisit simulate --preset demo --session 1 --out data/demo-s1   # same city, another route\n"
        "  revisit simulate --list-presets");
    cmd->add_option("--preset", options->preset, "world + sensor preset (see --list-presets)")->capture_default_str();
    cmd->add_option("--out", options->out, "output KITTI folder or .rawlog[.gz] file");
    cmd->add_option("--seed", options->seed, "random seed (default: the preset's)");
    cmd->add_option("--scans", options->max_scans, "stop after this many scans (default: the whole route)");
    cmd->add_option("--trajectory", options->trajectory,
                    "drive this KITTI/TUM trajectory through a street world built along it (the preset gives the "
                    "sensor and densities)")
        ->check(CLI::ExistingFile);
    cmd->add_option("--session", options->session,
                    "another session in the same world: K > 0 drives another route (same world seed, route seed "
                    "derived from seed and K)")
        ->check(CLI::NonNegativeNumber);
    cmd->add_flag("--force", options->force, "write into an existing non-empty folder / overwrite a file");
    cmd->add_flag("--quiet", options->quiet, "no progress output");
    cmd->add_flag("--list-presets", options->list, "print the preset names and exit");
    cmd->callback([options, &action] { action = [options] { return RunSimulate(*options); }; });
}

}  // namespace revisit::app
