#pragma once
/// `revisit batch --engine slurm`: a job array (one task per sequence) and a merge job that waits for it
/// (`--dependency=afterok`), submitted with sbatch and followed with squeue and sacct (scontrol when the
/// cluster keeps no accounting). Slurm schedules; this only writes scripts and reads states.
#include <ostream>
#include <string>
#include <vector>

#include "fleet/batch_plan.hpp"
#include "config/config.hpp"

namespace revisit {

/// The array script running the tasks `indices` (task id = manifest index), resources from `fleet`.
std::string SlurmArrayScript(const BatchPlan& plan, const std::vector<std::size_t>& indices, const FleetConfig& fleet);
/// The merge job's script (submitted with --dependency=afterok:<array job id>).
std::string SlurmMergeScript(const BatchPlan& plan, const FleetConfig& fleet);

/// Final state of one job or array task as Slurm reports it.
struct SlurmJobState {
    std::string id;     ///< "123_4" for array task 4 of job 123, "125" for a plain job
    std::string state;  ///< COMPLETED, FAILED, CANCELLED, TIMEOUT, OUT_OF_MEMORY, PENDING, RUNNING, ...
    std::string exit_code;
};

/// Parses `sacct -n -P -o JobID,State,ExitCode` output (steps such as 123_4.batch are skipped).
std::vector<SlurmJobState> ParseSacct(const std::string& text);
/// Parses `scontrol -o show job` output (one line per job or array task).
std::vector<SlurmJobState> ParseScontrol(const std::string& text);

struct SlurmOutcome {
    std::string array_job;  ///< "" when no task had to run (resume with every run finished)
    std::string merge_job;
    std::vector<std::size_t> failed;  ///< task indices that did not finish
    bool merge_ok = false;
    int merge_exit = -1;
};

/// Writes the scripts to <out>/slurm/, submits them with sbatch (unless `dry_run`: prints them to `log`
/// instead), then polls every `poll_seconds` until the merge job leaves the queue; lists failed tasks with
/// their logs. Throws std::runtime_error when sbatch is missing or refuses a script (its message included).
SlurmOutcome RunOnSlurm(const BatchPlan& plan, const std::vector<std::size_t>& indices, const FleetConfig& fleet,
                        bool dry_run, double poll_seconds, std::ostream& log);

}  // namespace revisit
