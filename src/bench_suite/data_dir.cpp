#include "bench_suite/data_dir.hpp"

#include <cstdlib>
#include <cstring>
#include <sstream>

#include "core/error.hpp"

#ifndef REVISIT_DEFAULT_DATA_DIR
#define REVISIT_DEFAULT_DATA_DIR "../shared/data"
#endif

namespace revisit {

std::filesystem::path DefaultDataDir() {
    const char* env = std::getenv("REVISIT_DATA");
    return env && *env ? std::filesystem::path(env) : std::filesystem::path(REVISIT_DEFAULT_DATA_DIR);
}

bool SkipMissingFromEnvironment() {
    const char* env = std::getenv("REVISIT_SKIP_MISSING");
    if (!env) return false;
    for (const char* yes : {"1", "true", "yes", "on"})
        if (std::strcmp(env, yes) == 0) return true;
    return false;
}

BenchDataOptions TakeBenchDataOptions(int& argc, char** argv) {
    BenchDataOptions options;
    options.data_dir = DefaultDataDir();
    options.skip_missing = SkipMissingFromEnvironment();
    int kept = 1;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        if (arg == "--skip-missing") {
            options.skip_missing = true;
        } else if (arg == "--data") {
            if (i + 1 >= argc) throw ConfigError("--data needs a folder");
            options.data_dir = argv[++i];
        } else if (arg.rfind("--data=", 0) == 0) {
            if (arg.size() == 7) throw ConfigError("--data= needs a folder");
            options.data_dir = arg.substr(7);
        } else {
            argv[kept++] = argv[i];
        }
    }
    argc = kept;
    return options;
}

void BenchFailures::NoteMissing(const std::string& description) { missing_.push_back(description); }

void BenchFailures::NoteFailed(const std::string& case_name, const std::string& reason) {
    failed_.push_back(case_name + ": " + reason);
}

std::string BenchFailures::Report(bool skip_missing) const {
    std::ostringstream out;
    if (!missing_.empty()) {
        out << missing_.size() << " case(s) did not run for missing data"
            << (skip_missing ? " (skipped as asked):\n" : ":\n");
        for (const auto& m : missing_) out << "  " << m << "\n";
        if (!skip_missing)
            out << "give the data folder with --data DIR or REVISIT_DATA, or skip these cases with --skip-missing "
                   "or REVISIT_SKIP_MISSING=1\n";
    }
    if (!failed_.empty()) {
        out << failed_.size() << " case(s) failed:\n";
        for (const auto& f : failed_) out << "  " << f << "\n";
    }
    return out.str();
}

int BenchFailures::ExitCode(bool skip_missing) const {
    if (!failed_.empty()) return 2;
    return missing_.empty() || skip_missing ? 0 : 2;
}

}  // namespace revisit
