/// `revisit batch MANIFEST --out DIR --engine local|slurm`: one run per sequence, then the merge.
#include <fstream>
#include <iostream>
#include <thread>

#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "core/error.hpp"
#include "io/output_folder.hpp"
#include "fleet/batch_local.hpp"
#include "fleet/batch_slurm.hpp"
#include "run_options.hpp"

namespace revisit::app {
namespace fs = std::filesystem;
namespace {
struct BatchOptions {
    std::string manifest;
    std::string out;
    std::string engine = "local";
    ConfigOptions config;
    int jobs = 1;
    double poll_seconds = 2.0;
    bool dry_run = false;
    bool resume = false;
    bool force = false;
};

/// Connected sessions of the merge, from its sessions.json ("" when there is none).
std::string MergeSummary(const fs::path& merge_dir) {
    std::ifstream in(merge_dir / "sessions.json");
    if (!in) return "";
    try {
        const auto j = nlohmann::json::parse(in);
        return std::to_string(j.at("connected_sessions").get<int>()) + " of " + std::to_string(j.at("sessions").size()) +
               " sessions in one frame, " + std::to_string(j.at("cross_closures").at("accepted").get<int>()) +
               " cross-session closures";
    } catch (const nlohmann::json::exception& e) {
        return std::string("unreadable sessions.json: ") + e.what();
    }
}

int RunBatch(const BatchOptions& o) {
    if (o.engine != "local" && o.engine != "slurm") throw ConfigError("--engine " + o.engine + ": local or slurm");
    const auto sequences = ReadManifest(o.manifest);
    const PipelineConfig config = ResolveConfig(o.config);  // the fleet section: Slurm resources
    const fs::path out = fs::absolute(o.out);
    if (o.resume) {
        if (!fs::is_directory(out)) throw DatasetError(out, "--resume: no such batch folder");
    } else if (!o.dry_run) {
        PrepareOutputFolder(out, o.force);
    }
    const bool slurm = o.engine == "slurm";
    const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
    const int threads = o.config.threads > 0 ? o.config.threads
                        : slurm            ? config.fleet.slurm_cpus_per_task
                                           : std::max(1, int(cores) / std::max(1, o.jobs));
    const BatchPlan plan = MakeBatchPlan(sequences, out, fs::read_symlink("/proc/self/exe"), o.config.configs,
                                         o.config.overrides, threads);
    std::vector<std::size_t> indices;
    for (const auto& task : plan.tasks) {
        if (!o.resume || !TaskFinished(task)) indices.push_back(task.index);
    }
    if (o.resume) std::cerr << "resume: " << indices.size() << " of " << plan.tasks.size() << " runs to (re)do\n";

    std::vector<std::size_t> failed;
    int merge_exit = -1;
    if (slurm) {
        const auto outcome = RunOnSlurm(plan, indices, config.fleet, o.dry_run, o.poll_seconds, o.dry_run ? std::cout : std::cerr);
        if (o.dry_run) return 0;
        failed = outcome.failed;
        merge_exit = outcome.merge_exit;
    } else {
        if (o.dry_run) {
            for (const auto i : indices) std::cout << ShellCommand(plan.executable, plan.tasks[i].arguments) << '\n';
            std::cout << ShellCommand(plan.executable, plan.merge_arguments) << '\n';
            return 0;
        }
        const auto outcome = RunLocally(plan, indices, o.jobs, std::cerr);
        failed = outcome.failed;
        merge_exit = outcome.merge_exit;
    }
    for (const auto i : failed) std::cout << "failed: " << plan.tasks[i].name << "  log " << plan.tasks[i].log.string() << '\n';
    if (!failed.empty()) {
        std::cout << failed.size() << " of " << plan.tasks.size() << " runs failed; fix and rerun with --resume\n";
        return 1;
    }
    const std::string merged = MergeSummary(plan.merge_dir);
    std::cout << "merge: " << (merged.empty() ? "no result" : merged) << " (" << plan.merge_dir.string() << ", exit "
              << merge_exit << ")\n";
    return merge_exit == 0 ? 0 : merge_exit == 3 ? 3 : 1;
}
}  // namespace

void AddBatchCommand(CLI::App& root, Action& action) {
    auto o = std::make_shared<BatchOptions>();
    auto* cmd = root.add_subcommand("batch", "Run a manifest of sequences (one run each), then merge them: locally or on Slurm");
    cmd->footer(
        "MANIFEST: YAML (sequences: [{path: DIR, config: NAME|FILE, reference: FILE, from: N, to: M}, ...]) or\n"
        "CSV (path[,config[,reference[,from[,to]]]] per line); relative paths are relative to the manifest, from/to\n"
        "cut one recording into sessions (revisit run --from/--to). OUT gets runs/NN_name,\n"
        "logs/NN_name.log, merge/ (revisit merge of every run) and, for Slurm, slurm/runs.sbatch and merge.sbatch.\n"
        "--engine slurm submits a job array (one task per sequence; fleet.slurm_* give CPUs, memory, time) and a\n"
        "merge job with --dependency=afterok, then follows squeue/sacct; OUT must be on a filesystem every node\n"
        "sees. --resume reruns only the runs that failed or are missing, then merges again.\n"
        "Examples:\n"
        "  revisit batch fleet.yaml --out /shared/fleet --engine slurm --set fleet.slurm_memory_mb=8000\n"
        "  revisit batch fleet.csv --out runs/fleet --engine local --jobs 2\n"
        "  revisit batch fleet.yaml --out /shared/fleet --engine slurm --dry-run");
    cmd->add_option("manifest", o->manifest, "YAML or CSV list of sequences")->required();
    cmd->add_option("--out", o->out, "batch folder (shared filesystem for Slurm)")->required();
    cmd->add_option("--engine", o->engine, "local or slurm")->capture_default_str();
    AddConfigOptions(*cmd, o->config);
    cmd->add_option("--jobs", o->jobs, "local: runs at the same time")->check(CLI::Range(1, 1024))->capture_default_str();
    cmd->add_option("--poll", o->poll_seconds, "slurm: seconds between squeue polls")->check(CLI::Range(0.1, 3600.0));
    cmd->add_flag("--dry-run", o->dry_run, "print the scripts (slurm) or commands (local); submit and run nothing");
    cmd->add_flag("--resume", o->resume, "rerun only failed or missing runs, then merge");
    cmd->add_flag("--force", o->force, "write into an existing non-empty folder");
    cmd->callback([o, &action] { action = [o] { return RunBatch(*o); }; });
}

}  // namespace revisit::app
