#pragma once
/// The main of every Google Benchmark binary in microbench/.
/// `--data DIR` (else $REVISIT_DATA, else ../shared/data) names the real-data folder and
/// `--skip-missing` (or REVISIT_SKIP_MISSING=1) allows cases to skip when their data is absent. A case
/// whose data is missing calls SkipForMissingData; at the end the binary lists every case that did not
/// run or failed, and exits 2 unless only data was missing and skipping was asked.
#include <benchmark/benchmark.h>

#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>

#include "bench_suite/data_dir.hpp"
#include "core/allocator.hpp"

namespace revisit::bench {

inline BenchDataOptions& DataOptions() {
    static BenchDataOptions options;
    return options;
}

/// The real-data folder this run uses.
inline const std::filesystem::path& DataDir() { return DataOptions().data_dir; }

inline constexpr const char* kMissingPrefix = "missing data: ";

/// Marks the running case as not run because `missing` is absent (the reporter collects it).
inline void SkipForMissingData(benchmark::State& state, const std::filesystem::path& missing) {
    state.SkipWithError((kMissingPrefix + missing.string()).c_str());
}

/// True when `path` exists; otherwise skips the case for missing data.
inline bool NeedData(benchmark::State& state, const std::filesystem::path& path) {
    if (std::filesystem::exists(path)) return true;
    SkipForMissingData(state, path);
    return false;
}

/// Forwards to the display reporter Google Benchmark would have used and collects the cases that
/// skipped with an error.
class FailureCollector : public benchmark::BenchmarkReporter {
public:
    explicit FailureCollector(benchmark::BenchmarkReporter* display) : display_(display) {}
    bool ReportContext(const Context& context) override {
        display_->SetOutputStream(&GetOutputStream());
        display_->SetErrorStream(&GetErrorStream());
        return display_->ReportContext(context);
    }
    void ReportRuns(const std::vector<Run>& runs) override {
        for (const auto& run : runs) {
            if (!run.error_occurred) continue;
            const std::string& message = run.error_message;
            if (message.rfind(kMissingPrefix, 0) == 0)
                failures.NoteMissing(run.benchmark_name() + ": " + message.substr(std::string(kMissingPrefix).size()) +
                                    " absent");
            else
                failures.NoteFailed(run.benchmark_name(), message);
        }
        display_->ReportRuns(runs);
    }
    void Finalize() override { display_->Finalize(); }

    BenchFailures failures;

private:
    std::unique_ptr<benchmark::BenchmarkReporter> display_;
};

inline int Main(int argc, char** argv) {
    // The allocator as `revisit` runs with it (apps/main.cpp): without its top pad, buffers freed by one
    // stage and allocated by the next map fresh pages (KITTI odometry in stages at 2 threads: 2.19 ms
    // per scan without, 1.9 with).
    TuneAllocator();
    try {
        DataOptions() = TakeBenchDataOptions(argc, argv);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "%s: %s\n", argv[0], e.what());
        return 1;
    }
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
    std::cerr << "data folder: " << DataDir().string() << (DataOptions().skip_missing ? " (--skip-missing)" : "")
              << "\n";
    FailureCollector collector(benchmark::CreateDefaultDisplayReporter());
    benchmark::RunSpecifiedBenchmarks(&collector);
    benchmark::Shutdown();
    std::cerr << collector.failures.Report(DataOptions().skip_missing);
    return collector.failures.ExitCode(DataOptions().skip_missing);
}

}  // namespace revisit::bench

#define REVISIT_BENCHMARK_MAIN() \
    int main(int argc, char** argv) { return revisit::bench::Main(argc, argv); }
