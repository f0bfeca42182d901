/// `revisit merge RUN_DIR... --out DIR`: finished runs as sessions of one map.
#include <iostream>

#include "commands.hpp"
#include "sessions/session_merge.hpp"
#include "run_options.hpp"

namespace revisit::app {
namespace {
struct MergeOptions {
    std::vector<std::string> runs;
    std::string out;
    std::vector<std::string> overrides;
    int threads = 0;
    bool force = false;
    bool allow_incomplete = false;
};

int RunMerge(const MergeOptions& o) {
    const auto threads = LimitThreads(o.threads);
    std::vector<std::filesystem::path> runs(o.runs.begin(), o.runs.end());
    const auto result = MergeRunFolders(runs, o.out, o.force, o.overrides, std::cerr, std::cout, o.allow_incomplete);
    for (const char connected : result.graph.connected) {
        if (!connected) return 3;  // written, but not every session is in the common frame
    }
    return 0;
}
}  // namespace

void AddMergeCommand(CLI::App& root, Action& action) {
    auto o = std::make_shared<MergeOptions>();
    auto* cmd = root.add_subcommand("merge", "Join finished runs (sessions) into one frame: cross-session closures, joint graph");
    cmd->footer(
        "Loads each run's closure database and local maps, finds closures between sessions with the same\n"
        "verification as in one run (RANSAC, 3D refinement, pairwise consistency, robust graph), optimizes all\n"
        "sessions jointly and writes sessions.json, cross_closures.csv, session_KK_poses_{kitti,tum}.txt and\n"
        "map_joint.ply. The order of the folders does not matter: sessions are ordered by dataset, --from, --to\n"
        "and folder, and session 0 (the anchor) gives the common frame. A session that no cross closure ties to\n"
        "the anchor is reported as unconnected (exit code 3) and left out of the common frame.\n"
        "Examples:\n"
        "  revisit merge runs/day1 runs/day2 runs/day3 --out runs/joint\n"
        "  revisit merge runs/a runs/b --out joint --set fleet.min_cross_closures=2");
    cmd->add_option("runs", o->runs, "finished run folders (revisit run --out)")->required()->expected(1, -1);
    cmd->add_option("--out", o->out, "output folder")->required();
    cmd->add_option("--set", o->overrides, "override one parameter of the anchor run's config; repeatable");
    cmd->add_option("--threads", o->threads, "worker threads (default: all cores)")->check(CLI::Range(0, 1024));
    cmd->add_flag("--force", o->force, "write into an existing non-empty folder");
    cmd->add_flag("--allow-incomplete", o->allow_incomplete,
                  "merge an interrupted run (run.json: complete = false) as it is, with a warning; refused otherwise");
    cmd->callback([o, &action] { action = [o] { return RunMerge(*o); }; });
}

}  // namespace revisit::app
