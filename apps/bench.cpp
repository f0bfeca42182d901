/// `revisit bench [--suite quick|full] [--out FILE.json] [--compare OLD.json]`: speed of every stage and
/// of the whole chain (issue 10), printed as a table and written as JSON.
#include <iostream>

#include "benchmark/record.hpp"
#include "benchmark/suite.hpp"
#include "commands.hpp"
#include "run_options.hpp"

namespace revisit::app {
namespace {
struct BenchCommandOptions {
    BenchOptions bench;
    std::string data, out, compare;
    int threads = 0;
};

int RunBench(const BenchCommandOptions& o) {
    const auto threads = LimitThreads(o.threads);
    BenchOptions bench = o.bench;
    bench.data_dir = o.data;
    bench.progress = [](const std::string& group) { ShowProgress("bench: " + group); };
    // Read the old record first: a bad file should fail before minutes of measuring.
    const std::optional<BenchRecord> old = o.compare.empty() ? std::nullopt : std::optional(ReadRecord(o.compare));
    const BenchRecord record = RunSuite(bench);
    EndProgress();
    std::cout << FormatRecord(record);
    if (!o.out.empty()) {
        WriteRecord(o.out, record);
        std::cout << "wrote " << o.out << '\n';
    }
    if (old) {
        std::cout << "\ncompared with " << o.compare << " (suite " << old->suite << ", " << old->started_utc << ", "
                  << old->machine.cores << " cores, " << old->machine.build_type << ")\n"
                  << FormatComparison(CompareRecords(*old, record));
    }
    return 0;
}
}  // namespace

void AddBenchCommand(CLI::App& root, Action& action) {
    auto o = std::make_shared<BenchCommandOptions>();
    o->data = DefaultDataDir().string();
    auto* cmd = root.add_subcommand("bench", "Measure the speed of every stage and of the whole chain");
    cmd->footer(
        "Each figure: median, min, max and spread over repeated runs after a warm-up, with the core count and\n"
        "build type. Generated data (simulator presets) always; real data (KITTI 00 scans, radish rawlogs)\n"
        "when --data exists. quick: under 3 minutes on 2 cores; full: larger sizes, ~15 minutes (it prints\n"
        "its duration). --compare prints new/old ratios: judge a change by ratios measured on one machine.\n"
        "Examples:\n"
        "  revisit bench --out before.json\n"
        "  revisit bench --compare before.json --out after.json\n"
        "  revisit bench --suite full --threads 2 --out full.json\n"
        "  revisit bench --only odometry,tree");
    cmd->add_option("--suite", o->bench.suite, "quick, full or tiny (seconds; for tests)")
        ->check(CLI::IsMember(SuiteNames()))
        ->capture_default_str();
    cmd->add_option("--out", o->out, "write the record as JSON");
    cmd->add_option("--compare", o->compare, "an earlier record (JSON): print new/old ratios")
        ->check(CLI::ExistingFile);
    cmd->add_option("--data", o->data,
                    "folder with kitti00_first16/ and radish/ (real-data cases; skipped when absent)")
        ->capture_default_str();
    cmd->add_option("--threads", o->threads, "TBB threads for the whole run (0: all cores); the '1t' figures use 1");
    cmd->add_option("--only", o->bench.groups, "only these case groups")
        ->delimiter(',')
        ->check(CLI::IsMember(CaseGroupNames()));
    cmd->callback([o, &action] { action = [o] { return RunBench(*o); }; });
}

}  // namespace revisit::app
