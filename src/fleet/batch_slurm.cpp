#include "fleet/batch_slurm.hpp"

#include <sys/wait.h>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "core/atomic_file.hpp"

namespace revisit {
namespace fs = std::filesystem;
namespace {

std::string Header(const std::string& name, const fs::path& output, const FleetConfig& fleet, int cpus) {
    std::ostringstream s;
    s << "#!/bin/bash\n"
      << "#SBATCH --job-name=" << name << '\n'
      << "#SBATCH --output=" << output.string() << '\n'
      << "#SBATCH --cpus-per-task=" << cpus << '\n'
      << "#SBATCH --mem=" << fleet.slurm_memory_mb << "M\n"
      << "#SBATCH --time=" << fleet.slurm_time_minutes << '\n';
    if (!fleet.slurm_partition.empty()) s << "#SBATCH --partition=" << fleet.slurm_partition << '\n';
    return s.str();
}

struct Captured {
    int status = -1;
    std::string output;
};

/// Runs a shell command and returns its exit status and stdout+stderr.
Captured Capture(const std::string& command) {
    Captured result;
    FILE* pipe = popen((command + " 2>&1").c_str(), "r");
    if (!pipe) return result;
    char buffer[4096];
    std::size_t n;
    while ((n = fread(buffer, 1, sizeof(buffer), pipe)) > 0) result.output.append(buffer, n);
    const int status = pclose(pipe);
    result.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return result;
}

std::string Submit(const std::string& arguments, const fs::path& script) {
    const auto submitted = Capture("sbatch --parsable " + arguments + ShellQuote(script.string()));
    if (submitted.status != 0) throw std::runtime_error("sbatch " + script.string() + " failed: " + submitted.output);
    std::string id = submitted.output.substr(0, submitted.output.find_first_of(";\n"));  // "id[;cluster]"
    if (id.empty()) throw std::runtime_error("sbatch " + script.string() + " printed no job id: " + submitted.output);
    return id;
}

std::string Field(const std::string& line, const std::string& key) {
    const auto start = line.find(' ' + key + '=') != std::string::npos ? line.find(' ' + key + '=') + 1
                       : line.rfind(key + '=', 0) == 0                ? 0
                                                                      : std::string::npos;
    if (start == std::string::npos) return "";
    const auto value = start + key.size() + 1;
    return line.substr(value, line.find(' ', value) - value);
}

std::vector<SlurmJobState> FinalStates(const std::string& jobs) {
    const auto accounted = Capture("sacct -n -P -o JobID,State,ExitCode -j " + jobs);
    auto states = accounted.status == 0 ? ParseSacct(accounted.output) : std::vector<SlurmJobState>{};
    if (!states.empty()) return states;
    // No accounting storage (a cluster without slurmdbd): the controller still knows recent jobs.
    std::string text;
    std::istringstream ids(jobs);
    for (std::string id; std::getline(ids, id, ',');) text += Capture("scontrol -o show job " + id).output;
    return ParseScontrol(text);
}

void Tail(const fs::path& file, std::ostream& log, std::size_t lines) {
    std::ifstream in(file);
    std::vector<std::string> last;
    for (std::string line; std::getline(in, line);) {
        last.push_back(line);
        if (last.size() > lines) last.erase(last.begin());
    }
    for (const auto& line : last) log << "    | " << line << '\n';
}

}  // namespace

std::string SlurmArrayScript(const BatchPlan& plan, const std::vector<std::size_t>& indices, const FleetConfig& fleet) {
    std::ostringstream s;
    s << Header("revisit-runs", plan.out / "logs" / "slurm_%A_%a.out", fleet, fleet.slurm_cpus_per_task);
    s << "#SBATCH --array=";
    for (std::size_t i = 0; i < indices.size(); ++i) s << (i ? "," : "") << indices[i];
    s << "\n# One `revisit run` per manifest sequence; the task id is the sequence's index.\n"
      << "# A log's name is removed first and opened without clobbering (set -C): a link planted there is\n"
      << "# replaced, never written through.\n"
      << "set -uC\n"
      << "case \"$SLURM_ARRAY_TASK_ID\" in\n";
    for (const std::size_t i : indices) {
        const auto& task = plan.tasks[i];
        s << "  " << i << ") rm -f -- " << ShellQuote(task.log.string()) << " && exec " << ShellCommand(plan.executable, task.arguments) << " > " << ShellQuote(task.log.string())
          << " 2>&1 ;;\n";
    }
    s << "esac\n"
      << "echo \"revisit batch: no task $SLURM_ARRAY_TASK_ID\" >&2\n"
      << "exit 2\n";
    return s.str();
}

std::string SlurmMergeScript(const BatchPlan& plan, const FleetConfig& fleet) {
    std::ostringstream s;
    s << Header("revisit-merge", plan.out / "logs" / "slurm_merge_%j.out", fleet, fleet.slurm_cpus_per_task)
      << "# The cross-session merge of every run; submitted with --dependency=afterok on the run array.\n"
      << "set -C\n"
      << "rm -f -- " << ShellQuote(plan.merge_log.string()) << " && exec " << ShellCommand(plan.executable, plan.merge_arguments)
      << " > " << ShellQuote(plan.merge_log.string()) << " 2>&1\n";
    return s.str();
}

std::vector<SlurmJobState> ParseSacct(const std::string& text) {
    std::vector<SlurmJobState> states;
    std::istringstream lines(text);
    for (std::string line; std::getline(lines, line);) {
        std::vector<std::string> fields;
        std::istringstream split(line);
        for (std::string field; std::getline(split, field, '|');) fields.push_back(field);
        if (fields.size() < 3 || fields[0].find('.') != std::string::npos) continue;  // job steps
        const std::string state = fields[1].substr(0, fields[1].find(' '));            // "CANCELLED by 0"
        states.push_back({fields[0], state, fields[2]});
    }
    return states;
}

std::vector<SlurmJobState> ParseScontrol(const std::string& text) {
    std::vector<SlurmJobState> states;
    std::istringstream lines(text);
    for (std::string line; std::getline(lines, line);) {
        const std::string job = Field(line, "JobId");
        if (job.empty()) continue;
        const std::string array = Field(line, "ArrayJobId");
        const std::string task = Field(line, "ArrayTaskId");
        const bool one_task = !array.empty() && !task.empty() && task.find_first_not_of("0123456789") == std::string::npos;
        states.push_back({one_task ? array + "_" + task : job, Field(line, "JobState"), Field(line, "ExitCode")});
    }
    return states;
}

SlurmOutcome RunOnSlurm(const BatchPlan& plan, const std::vector<std::size_t>& indices, const FleetConfig& fleet,
                        bool dry_run, double poll_seconds, std::ostream& log) {
    SlurmOutcome outcome;
    const fs::path folder = plan.out / "slurm";
    fs::create_directories(folder);
    fs::create_directories(plan.out / "logs");
    const fs::path array_script = folder / "runs.sbatch";
    const fs::path merge_script = folder / "merge.sbatch";
    if (!indices.empty()) WriteFileAtomically(array_script, SlurmArrayScript(plan, indices, fleet));
    WriteFileAtomically(merge_script, SlurmMergeScript(plan, fleet));
    if (dry_run) {
        if (!indices.empty()) log << "# " << array_script.string() << '\n' << SlurmArrayScript(plan, indices, fleet) << '\n';
        log << "# " << merge_script.string() << '\n' << SlurmMergeScript(plan, fleet) << '\n'
            << "# submit: sbatch --parsable " << array_script.string() << "; then sbatch --dependency=afterok:<array id> "
            << merge_script.string() << '\n';
        return outcome;
    }
    if (Capture("command -v sbatch").status != 0) throw std::runtime_error("--engine slurm: sbatch is not installed (Debian: slurm-wlm)");
    if (!indices.empty()) outcome.array_job = Submit("", array_script);
    outcome.merge_job = Submit(outcome.array_job.empty() ? "" : "--dependency=afterok:" + outcome.array_job + " ", merge_script);
    log << "submitted: run array " << (outcome.array_job.empty() ? "(none: every run finished)" : outcome.array_job) << " ("
        << indices.size() << " tasks), merge job " << outcome.merge_job << '\n';

    const std::string jobs = (outcome.array_job.empty() ? "" : outcome.array_job + ",") + outcome.merge_job;
    std::string last;
    int failed_polls = 0;
    for (;;) {
        const auto queue = Capture("squeue -h -o '%i %T %r' -j " + jobs);
        failed_polls = queue.status == 0 ? 0 : failed_polls + 1;
        if (failed_polls >= 30) throw std::runtime_error("squeue failed 30 times in a row: " + queue.output);
        std::map<std::string, int> counts;
        bool merge_blocked = false, array_left = false;
        std::istringstream lines(queue.output);
        for (std::string id, state, reason; lines >> id >> state >> reason;) {
            if (id == outcome.merge_job) merge_blocked = reason == "DependencyNeverSatisfied";
            else array_left = true;
            ++counts[state];
        }
        std::string summary;
        for (const auto& [state, n] : counts) summary += " " + state + "=" + std::to_string(n);
        if (summary != last && !summary.empty()) log << "queue:" << summary << '\n';
        last = summary;
        if (counts.empty() && queue.status == 0) break;
        if (merge_blocked && !array_left) {
            log << "a run failed: cancelling the merge job " << outcome.merge_job << '\n';
            Capture("scancel " + outcome.merge_job);
            break;
        }
        if (queue.status != 0 && queue.output.find("Invalid job id") != std::string::npos) break;  // purged
        std::this_thread::sleep_for(std::chrono::duration<double>(poll_seconds));
    }

    std::map<std::string, SlurmJobState> states;
    for (const auto& s : FinalStates(jobs)) states[s.id] = s;
    for (const std::size_t i : indices) {
        if (TaskFinished(plan.tasks[i])) continue;
        outcome.failed.push_back(i);
        const auto it = states.find(outcome.array_job + "_" + std::to_string(i));
        log << "FAILED task " << i << " (" << plan.tasks[i].name << "): "
            << (it == states.end() ? "no Slurm record" : it->second.state + " exit " + it->second.exit_code)
            << "; log " << plan.tasks[i].log.string() << '\n';
        Tail(plan.tasks[i].log, log, 5);
    }
    const auto merge = states.find(outcome.merge_job);
    if (merge != states.end()) {
        const std::string code = merge->second.exit_code.substr(0, merge->second.exit_code.find(':'));
        outcome.merge_exit = code.empty() ? -1 : std::stoi(code);
        log << "merge job " << outcome.merge_job << ": " << merge->second.state << " exit " << merge->second.exit_code
            << "; log " << plan.merge_log.string() << '\n';
    }
    outcome.merge_ok = fs::exists(plan.merge_dir / "sessions.json") && outcome.failed.empty() &&
                       (outcome.merge_exit == 0 || outcome.merge_exit == 3);
    return outcome;
}

}  // namespace revisit
