#pragma once
/// Where the benchmarks find their real data, and what they do when it is missing (issue 19: benchmarks
/// that cannot lie). Every micro-benchmark in microbench/ and `revisit bench` resolve the folder the same
/// way: --data DIR, else $REVISIT_DATA, else the compiled-in <source>/../shared/data. Missing data is an
/// error (non-zero exit) unless --skip-missing or REVISIT_SKIP_MISSING=1 asks to skip; either way the
/// cases that did not run are named.
#include <filesystem>
#include <string>
#include <vector>

namespace revisit {

struct BenchDataOptions {
    std::filesystem::path data_dir;  ///< folder with kitti00_first16/, kitti_gt_poses/, radish/
    bool skip_missing = false;       ///< missing data skips the cases that need it instead of failing the run
};

/// $REVISIT_DATA, else <source dir>/../shared/data as compiled in.
std::filesystem::path DefaultDataDir();

/// $REVISIT_SKIP_MISSING is set to 1, true, yes or on.
bool SkipMissingFromEnvironment();

/// Takes --data DIR, --data=DIR and --skip-missing out of argv (the rest is left for Google Benchmark's
/// own flags) over the environment's defaults. Throws ConfigError for --data without a value.
BenchDataOptions TakeBenchDataOptions(int& argc, char** argv);

/// The cases of one benchmark process that did not run or failed, with the reason.
class BenchFailures {
public:
    /// A case did not run for missing data: "<case>: <what is absent>".
    void NoteMissing(const std::string& description);
    /// `case_name` failed for another reason (a broken fixture, an empty result).
    void NoteFailed(const std::string& case_name, const std::string& reason);

    bool empty() const { return missing_.empty() && failed_.empty(); }
    const std::vector<std::string>& missing() const { return missing_; }
    const std::vector<std::string>& failed() const { return failed_; }

    /// Lines naming every case that did not run and why, and what to do; "" when all ran.
    std::string Report(bool skip_missing) const;
    /// 0 when every case ran, or when only data was missing and skipping was asked; otherwise 2.
    int ExitCode(bool skip_missing) const;

private:
    std::vector<std::string> missing_, failed_;
};

}  // namespace revisit
