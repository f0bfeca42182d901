/// `revisit eval RUN_DIR`: (re)computes the metrics of a finished run.
#include <iostream>

#include "commands.hpp"
#include "pipeline/evaluate.hpp"
#include "runfolder/run_files.hpp"
#include "pipeline/summary.hpp"
#include "run_options.hpp"

namespace revisit::app {
namespace {
struct EvalOptions {
    std::string run;
    int threads = 0;
    bool quiet = false;
};

int RunEval(const EvalOptions& o) {
    const auto threads = LimitThreads(o.threads);
    const RunFolder run = RunFolder::Open(o.run);
    // The run's own resolved configuration: the same parameters that produced it.
    const PipelineConfig config = LoadConfig({run.config().string()}, {});
    RunOptions options = ReadRunOptions(run);
    options.quiet = o.quiet;
    const RunState state = ReadRunState(run);
    const auto evaluation = EvaluateRun(run, state, options, config, std::cerr);
    if (!evaluation) {
        std::cerr << "revisit: " << o.run << ": the run has no reference poses; nothing to evaluate (run with --gt FILE)\n";
        return 1;
    }
    PrintRunSummary(std::cout, state, evaluation);
    std::cout << "\nwrote " << run.metrics_json().string() << ", pr_curve_<method>.csv, comparison.md\n";
    return 0;
}
}  // namespace

void AddEvalCommand(CLI::App& root, Action& action) {
    auto o = std::make_shared<EvalOptions>();
    auto* cmd = root.add_subcommand("eval", "Recompute precision/recall/F1 and APE of a finished run");
    cmd->footer(
        "Ground-truth closures (cached in the run folder, reused while the poses and parameters are the same),\n"
        "the PR sweep of density maps, the elevation-image ablation and the ScanContext baseline on the same\n"
        "scan pairs, map-level accuracy, and APE/RPE/KITTI errors before and after correction. Re-reads the\n"
        "run's dataset for the scans the ground truth needs.\n"
        "Example:\n"
        "  revisit eval reports/latest");
    cmd->add_option("run", o->run, "run folder written by `revisit run`")->required();
    cmd->add_option("--threads", o->threads, "worker threads (default: all cores)");
    cmd->add_flag("--quiet", o->quiet, "no progress output");
    cmd->callback([o, &action] { action = [o] { return RunEval(*o); }; });
}

}  // namespace revisit::app
