/// `revisit run DATASET`: the whole chain into a run folder, then evaluation and the report.
#include <algorithm>
#include <iostream>

#include "commands.hpp"
#include "core/error.hpp"
#include "pipeline/interrupt.hpp"
#include "pipeline/run_and_report.hpp"
#include "sessions/session_merge.hpp"
#include "run_options.hpp"

namespace revisit::app {
namespace fs = std::filesystem;
namespace {

struct RunCommandOptions {
    RunOptions run;
    ConfigOptions config;
    std::string poses = "odometry";
    std::string out;
    long long from = 0;  ///< signed: a negative index is named as an error, not wrapped around
    long long to = 0;
    bool has_to = false;
    std::vector<std::string> against;  ///< earlier runs: merge with them after this run
    bool allow_incomplete = false;     ///< an interrupted earlier run is merged, with a warning
};

int RunRun(RunCommandOptions& o) {
    std::vector<fs::path> sessions;
    if (!o.against.empty()) {
        // Check the earlier runs before spending time on this one; without --config, take the first one's
        // settings, so that this run's descriptors are comparable with theirs.
        const auto earlier = LoadSessionRuns({o.against.begin(), o.against.end()}, o.allow_incomplete, &std::cerr);
        for (const auto& session : earlier) sessions.push_back(session.folder);
        if (o.config.configs.empty()) o.config.configs.push_back(RunFolder(earlier.front().folder).config().string());
    }
    const auto config = ResolveConfigFor(o.config, o.run.dataset, std::cerr);
    const auto threads = LimitThreads(o.config.threads);
    if (o.poses == "odometry") o.run.poses = PoseSource::kOdometry;
    else if (o.poses == "dataset") o.run.poses = PoseSource::kDataset;
    else if (o.poses == "prior") o.run.poses = PoseSource::kPrior;
    else {
        o.run.poses = PoseSource::kFile;
        o.run.poses_file = o.poses;
    }
    if (o.from < 0) throw ConfigError("--from " + std::to_string(o.from) + ": a scan index is 0 or more");
    if (o.has_to && o.to < 0) throw ConfigError("--to " + std::to_string(o.to) + ": a scan index is 0 or more");
    o.run.from = static_cast<std::size_t>(o.from);
    if (o.has_to) o.run.to = static_cast<std::size_t>(o.to);
    CheckScanRange(o.run, std::nullopt);
    const bool default_out = o.out.empty();
    o.run.out = default_out ? RunFolder::DefaultPath("reports", o.run.dataset) : fs::path(o.out);
    if (!o.run.quiet) std::cerr << "revisit: " << o.run.dataset.string() << " -> " << o.run.out.string() << '\n';
    const RunState state = RunAndReport(o.run, config, std::cerr, std::cout);
    if (default_out) RunFolder::UpdateLatestLink(o.run.out);
    if (!sessions.empty() && state.complete && !InterruptRequested()) {
        sessions.push_back(o.run.out);
        const auto merged = MergeRunFolders(sessions, o.run.out / "merge", true, o.config.overrides, std::cerr, std::cout,
                                            o.allow_incomplete);
        if (std::count(merged.graph.connected.begin(), merged.graph.connected.end(), 0) > 0) return 3;  // as revisit merge
    }
    return state.complete && !InterruptRequested() ? 0 : 130;
}
}  // namespace

void AddRunCommand(CLI::App& root, Action& action) {
    auto o = std::make_shared<RunCommandOptions>();
    auto* cmd = root.add_subcommand("run", "Find loop closures and correct the trajectory of a dataset");
    cmd->footer(
        "Streams the dataset: odometry, local maps, density images, ORB, Hamming tree, RANSAC, 3D refinement\n"
        "and the pose graph, as scans arrive. Writes a run folder (docs/formats.md lists its files) and, when the\n"
        "dataset has reference poses or --gt is given, precision/recall/F1 and APE. Ctrl-C stops cleanly\n"
        "and writes what was computed (run.json: complete = false).\n"
        "Settings no --config/--set gives are derived from the first scans (ranges, field of view, points per\n"
        "scan, a 2D laser's aperture measured against its wheel odometry) and printed with the reasons.\n"
        "Examples:\n"
        "  revisit run ~/kitti/sequences/00 --config kitti\n"
        "  revisit run intel.rawlog --config indoor2d --out runs/intel   (the 180-deg aperture is measured)\n"
        "  revisit run seq/ --poses dataset --set density.resolution=0.2 --threads 2\n"
        "  revisit run day2/ --against runs/day1 --out runs/day2   (joint result in runs/day2/merge)");
    cmd->add_option("dataset", o->run.dataset, "KITTI folder, .pcd/.ply folder, .rawlog[.gz], ROS bag (.mcap, .bag, rosbag2 folder) or sim:PRESET")->required();
    AddConfigOptions(*cmd, o->config);
    cmd->add_option("--topic", "ROS bags: the scan topic (sets input.topic)")
        ->each([o](const std::string& topic) { o->config.overrides.push_back("input.topic=" + topic); });
    cmd->add_option("--out", o->out, "run folder (default: reports/<dataset>-<time>, with a 'latest' link)");
    cmd->add_option("--poses", o->poses, "odometry (compute), dataset (use its reference poses), prior (use its odometry prior, e.g. wheel odometry, as it is) or a KITTI/TUM FILE")->capture_default_str();
    cmd->add_option("--gt", o->run.gt_file, "ground-truth trajectory (KITTI, TUM or sec,nsec,x,y,z,qx,qy,qz,qw CSV) for evaluation");
    cmd->add_option("--from", o->from, "first scan index to use (a folder or sim: starts there directly; a bag or log file reads and drops the scans before it, with their own progress)");
    cmd->add_option("--to", o->to, "last scan index to use (inclusive)")->each([o](const std::string&) { o->has_to = true; });
    cmd->add_option("--against", o->against,
                    "an earlier run folder (repeatable): also find closures with its session and write the joint "
                    "result to OUT/merge (as revisit merge); without --config, its config.yaml is used");
    cmd->add_flag("--allow-incomplete", o->allow_incomplete,
                  "with --against: merge an interrupted earlier run (run.json: complete = false) as it is, with a "
                  "warning; refused otherwise");
    cmd->add_flag("--force", o->run.force, "write into an existing non-empty run folder");
    cmd->add_flag("--quiet", o->run.quiet, "no progress output");
    cmd->add_flag("--allow-truncated", o->run.allow_truncated,
                  "a damaged or truncated rawlog or MCAP: use the scans read before the damage (run.json: truncated)");
    cmd->callback([o, &action] { action = [o] { return RunRun(*o); }; });
}

}  // namespace revisit::app
