/// `revisit eval RUN_DIR`: (re)computes the metrics of a finished run.
#include <fstream>
#include <iomanip>
#include <iostream>

#include "commands.hpp"
#include "core/error.hpp"
#include "evaluation/relation_metric.hpp"
#include "io/trajectory_io.hpp"
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
    std::string relations;  ///< a .relations file: only the relation metric
};

/// The relation metric (Kuemmerle et al. 2009) of the run's odometry and corrected trajectory.
int RunRelations(const EvalOptions& o) {
    const RunFolder run = RunFolder::Open(o.run);
    std::ifstream in(o.relations);
    if (!in) throw DatasetError(o.relations, "cannot be read");
    const auto relations = ParseRelations(in, o.relations);
    std::cout << "relation metric (Kuemmerle et al. 2009), " << relations.size() << " relations of " << o.relations << ":\n";
    std::cout << "  trajectory   used  unmatched   trans mean [m]  trans std   trans^2 mean [m^2]   rot mean [deg]  rot std   rot^2 mean [deg^2]\n";
    bool any = false;
    for (const auto& [name, file] : {std::pair<std::string, std::filesystem::path>{"odometry", run.odometry_tum()},
                                     std::pair<std::string, std::filesystem::path>{"corrected", run.corrected_tum()}}) {
        if (!std::filesystem::exists(file)) continue;
        const Trajectory trajectory = ReadTumPoses(file);
        if (!trajectory.has_timestamps()) continue;
        const RelationErrors e = EvaluateRelations(trajectory, relations);
        any = any || e.num_used > 0;
        std::cout << std::fixed << std::setprecision(4) << "  " << std::left << std::setw(11) << name << std::right << std::setw(6)
                  << e.num_used << std::setw(11) << e.num_unmatched << std::setw(17) << e.translation.mean << std::setw(11)
                  << e.translation.std << std::setw(21) << e.translation_squared.mean << std::setw(17) << e.rotation_deg.mean
                  << std::setw(10) << e.rotation_deg.std << std::setw(21) << e.rotation_deg_squared.mean << '\n';
    }
    if (!any) {
        std::cerr << "revisit: " << o.relations << ": no relation's stamps match the run's pose stamps (a log without times?)\n";
        return 1;
    }
    return 0;
}

int RunEval(const EvalOptions& o) {
    const auto threads = LimitThreads(o.threads);
    if (!o.relations.empty()) return RunRelations(o);
    const RunFolder run = RunFolder::Open(o.run);
    // The run's own resolved configuration: the same parameters that produced it.
    const PipelineConfig config = LoadConfig({run.config().string()}, {});
    RunOptions options = ReadRunOptions(run);
    options.quiet = o.quiet;
    const RunState state = ReadRunState(run, false);
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
        "  revisit eval reports/latest\n"
        "  revisit eval reports/latest --relations intel.relations");
    cmd->add_option("run", o->run, "run folder written by `revisit run`")->required();
    cmd->add_option("--threads", o->threads, "worker threads (default: all cores)");
    cmd->add_flag("--quiet", o->quiet, "no progress output");
    cmd->add_option("--relations", o->relations,
                    "a .relations file (t1 t2 x y z roll pitch yaw per line): print the relation metric of the odometry and the\n"
                    "corrected trajectory (Kuemmerle et al. 2009) instead of the other metrics");
    cmd->callback([o, &action] { action = [o] { return RunEval(*o); }; });
}

}  // namespace revisit::app
