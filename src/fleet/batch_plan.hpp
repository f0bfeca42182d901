#pragma once
/// `revisit batch`: a manifest of sequences becomes one `revisit run` per sequence and a final
/// `revisit merge` (issue 20). This file is the plan (commands, folders, logs) and what is finished;
/// batch_slurm.hpp turns it into Slurm scripts, batch_local.hpp runs it on this machine.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace revisit {

/// One manifest line: a dataset, optionally its own config (file or preset) and reference trajectory.
struct BatchSequence {
    std::filesystem::path path;
    std::string config;                 ///< "" : the batch's --config/--set only
    std::filesystem::path reference;    ///< "" : the dataset's own poses, if any
    std::optional<std::size_t> from;    ///< first scan (revisit run --from), e.g. one half of a recording
    std::optional<std::size_t> to;      ///< last scan, inclusive
};

/// Reads a manifest: YAML (`sequences:` a list of {path, config, reference, from, to}) or CSV
/// (`path[,config[,reference[,from[,to]]]]` per line, an optional header line starting with `path`, `#` comments). Relative paths are relative to
/// the manifest's folder. Throws DatasetError naming the file (and line for CSV) on anything malformed.
std::vector<BatchSequence> ReadManifest(const std::filesystem::path& manifest);

struct BatchTask {
    std::size_t index = 0;
    std::string name;                    ///< NN_<dataset name>[_from-to]: the run folder and log name
    std::filesystem::path run_dir;       ///< <out>/runs/<name>
    std::filesystem::path log;           ///< <out>/logs/<name>.log
    std::vector<std::string> arguments;  ///< of the revisit executable: run DATASET --out ...
};

struct BatchPlan {
    std::filesystem::path executable;    ///< the revisit binary every task runs (absolute)
    std::filesystem::path out;           ///< absolute; on a filesystem every node sees
    std::vector<BatchTask> tasks;
    std::vector<std::string> merge_arguments;  ///< merge RUN... --out <out>/merge --force
    std::filesystem::path merge_dir;
    std::filesystem::path merge_log;
};

/// The commands of a batch. `configs` / `overrides` apply to every run (before a sequence's own config);
/// `threads` > 0 is passed as --threads.
BatchPlan MakeBatchPlan(const std::vector<BatchSequence>& sequences, const std::filesystem::path& out,
                        const std::filesystem::path& executable, const std::vector<std::string>& configs,
                        const std::vector<std::string>& overrides, int threads);

/// A task is finished when its run folder holds a complete run (run.json complete, the database written).
bool TaskFinished(const BatchTask& task);

/// `word` quoted for a POSIX shell (single quotes).
std::string ShellQuote(const std::string& word);
/// The command line of `arguments` run by `executable`, quoted for a shell.
std::string ShellCommand(const std::filesystem::path& executable, const std::vector<std::string>& arguments);

}  // namespace revisit
