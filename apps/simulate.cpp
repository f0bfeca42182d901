/// `revisit simulate --preset NAME --out DIR`: a synthetic, ground-truthed sequence.
#include <cmath>
#include <iostream>
#include <optional>

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
    double length = 0.0;  ///< [m] 0: the preset's route
    std::string trajectory;
    int session = 0;
    std::optional<double> scale_bias;     ///< odometry prior: relative error of travelled distance
    std::optional<double> yaw_bias_deg;   ///< [deg/s] odometry prior: initial yaw-rate bias
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
    if (options.length > 0.0) {
        if (!options.trajectory.empty()) throw std::runtime_error("simulate: --length and --trajectory exclude each other");
        config = WithRouteLength(config, options.length);
    }
    config.session = options.session;
    if (options.scale_bias) config.odometry.speed_scale_bias = *options.scale_bias;
    if (options.yaw_bias_deg) config.odometry.yaw_rate_bias = *options.yaw_bias_deg * M_PI / 180.0;
    if (!options.trajectory.empty()) config = AlongTrajectory(config, options.trajectory);
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
        "an MRPT rawlog with ground truth and a drifting odometry prior (--odometry-scale-bias,\n"
        "--odometry-yaw-bias set its drift: a strong one leaves the loops to place recognition).\n"
        "Examples:\n"
        "  revisit simulate --preset demo --out data/demo\n"
        "  revisit simulate --preset indoor-2d-360 --out indoor.rawlog.gz --seed 7\n"
        "  revisit simulate --preset city-64 --trajectory ../shared/data/kitti_gt_poses/00.txt --out sim00\n"
        "  revisit simulate --preset demo --session 1 --out data/demo-s1   # same city, another route\n"
        "  revisit simulate --preset demo --out drift.rawlog --odometry-scale-bias 0.05 --odometry-yaw-bias 0.5\n"
        "  revisit simulate --preset highway-64 --length 25000 --out highway-25km.rawlog   # ~10,000 scans\n"
        "  revisit simulate --list-presets");
    cmd->add_option("--preset", options->preset, "world + sensor preset (see --list-presets)")->capture_default_str();
    cmd->add_option("--out", options->out, "output KITTI folder or .rawlog[.gz] file");
    cmd->add_option("--seed", options->seed, "random seed (default: the preset's)");
    cmd->add_option("--scans", options->max_scans, "stop after this many scans (default: the whole route)");
    cmd->add_option("--length", options->length,
                    "route length [m] of a city or highway preset (default: the preset's; the route also drives every planned "
                    "revisit, so it can come out longer); the world grows with it, "
                    "e.g. --preset highway-64 --length 25000 for the paper's highway scale")
        ->check(CLI::Range(100.0, 500000.0));
    cmd->add_option("--trajectory", options->trajectory,
                    "drive this KITTI/TUM trajectory through a street world built along it (the preset gives the "
                    "sensor and densities)")
        ->check(CLI::ExistingFile);
    cmd->add_option("--session", options->session,
                    "another session in the same world: K > 0 drives another route (same world seed, route seed "
                    "derived from seed and K)")
        ->check(CLI::NonNegativeNumber);
    cmd->add_option("--odometry-scale-bias", options->scale_bias,
                    "rawlog odometry prior: relative error of the travelled distance (default: the preset's, 0.01-0.02; 0.05 drifts like poor wheel odometry)")
        ->check(CLI::Range(-0.5, 0.5));
    cmd->add_option("--odometry-yaw-bias", options->yaw_bias_deg,
                    "rawlog odometry prior: initial yaw-rate bias [deg/s] (default: the preset's, 0.11-0.29; it also random-walks)")
        ->check(CLI::Range(-10.0, 10.0));
    cmd->add_flag("--force", options->force, "write into an existing non-empty folder / overwrite a file");
    cmd->add_flag("--quiet", options->quiet, "no progress output");
    cmd->add_flag("--list-presets", options->list, "print the preset names and exit");
    cmd->callback([options, &action] { action = [options] { return RunSimulate(*options); }; });
}

}  // namespace revisit::app
