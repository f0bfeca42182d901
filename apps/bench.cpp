/// `revisit bench [--suite quick|full] [--out FILE.json] [--compare OLD.json] [--reference REF.json]`: speed
/// of every stage and of the whole chain (issue 10), printed as a table and written as JSON. Missing real
/// data fails the command unless --skip-missing (issue 19).
#include <algorithm>
#include <iostream>

#include "bench_suite/record.hpp"
#include "bench_suite/suite.hpp"
#include "commands.hpp"
#include "run_options.hpp"

namespace revisit::app {
namespace {
struct BenchCommandOptions {
    BenchOptions bench;
    std::string data, out, compare, reference;
    int threads = 0;
    bool skip_missing = SkipMissingFromEnvironment();
};

int RunBench(const BenchCommandOptions& o) {
    const auto threads = LimitThreads(o.threads);
    BenchOptions bench = o.bench;
    bench.data_dir = o.data;
    bench.progress = [](const std::string& group) { ShowProgress("bench: " + group); };
    // Read the old record first: a bad file should fail before minutes of measuring.
    const std::optional<BenchRecord> old = o.compare.empty() ? std::nullopt : std::optional(ReadRecord(o.compare));
    const std::optional<BenchRecord> reference =
        o.reference.empty() ? std::nullopt : std::optional(ReadRecord(o.reference));
    if (!o.skip_missing && !std::filesystem::exists(bench.data_dir)) {
        std::cerr << "revisit bench: data folder " << bench.data_dir.string()
                  << " absent: the real-data cases cannot run. Give it with --data DIR or REVISIT_DATA, or skip "
                     "those cases with --skip-missing (REVISIT_SKIP_MISSING=1)\n";
        return 2;
    }
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
    if (reference) {
        std::cout << "\nper stage against the reference " << o.reference << " (suite " << reference->suite << ", "
                  << reference->started_utc << ", " << reference->machine.cores << " cores, "
                  << reference->machine.build_type << ")\n"
                  << FormatStageRatios(StageRatios(CompareRecords(*reference, record)));
    }
    // Cases that did not run make the figures incomplete: missing data fails unless skipping was asked,
    // a case that could not run for another reason (too few matches, too few scans) always fails.
    BenchFailures failures;
    for (const auto& s : record.skipped) {
        const bool missing = s.find(" absent") != std::string::npos || s.find("no data folder") != std::string::npos ||
                             s.find("no --data") != std::string::npos;
        if (missing) failures.NoteMissing(s);
        else failures.NoteFailed(s.substr(0, s.find(':')), s.substr(std::min(s.size(), s.find(':') + 2)));
    }
    if (!failures.empty()) std::cerr << failures.Report(o.skip_missing);
    return failures.ExitCode(o.skip_missing);
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
        "its duration). --compare prints new/old ratios and marks figures SLOWER beyond both runs' spread;\n"
        "--reference prints the speedup per stage against a record from another build. Judge a change by ratios\n"
        "measured on one machine. Missing real data (a case that cannot run) exits 2 unless --skip-missing.\n"
        "Examples:\n"
        "  revisit bench --out before.json\n"
        "  revisit bench --compare before.json --out after.json\n"
        "  revisit bench --suite full --threads 2 --out full.json\n"
        "  revisit bench --only odometry,tree\n"
        "  revisit bench --reference release-0.1.json --skip-missing");
    cmd->add_option("--suite", o->bench.suite, "quick, full or tiny (seconds; for tests)")
        ->check(CLI::IsMember(SuiteNames()))
        ->capture_default_str();
    cmd->add_option("--out", o->out, "write the record as JSON");
    cmd->add_option("--compare", o->compare, "an earlier record (JSON): print new/old ratios")
        ->check(CLI::ExistingFile);
    cmd->add_option("--data", o->data,
                    "folder with kitti00_first16/ and radish/ (real-data cases); default $REVISIT_DATA, else "
                    "../shared/data")
        ->capture_default_str();
    cmd->add_flag("--skip-missing", o->skip_missing,
                  "skip the cases whose data is absent (listed) instead of failing (exit 2); also REVISIT_SKIP_MISSING=1");
    cmd->add_option("--reference", o->reference,
                    "a record (JSON) from another build or machine: print per stage the speedup against it")
        ->check(CLI::ExistingFile);
    cmd->add_option("--threads", o->threads, "TBB threads for the whole run (0: all cores); the '1t' figures use 1");
    cmd->add_option("--only", o->bench.groups, "only these case groups")
        ->delimiter(',')
        ->check(CLI::IsMember(CaseGroupNames()));
    cmd->callback([o, &action] { action = [o] { return RunBench(*o); }; });
}

}  // namespace revisit::app
