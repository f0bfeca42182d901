// Benchmarks that cannot lie (issue 19): where the data folder comes from, and the exit code when the
// data a case needs is missing, for the microbench/ binaries' helper and for `revisit bench`.
#include <gtest/gtest.h>

#include <cstdlib>
#include <string>
#include <vector>

#include "bench_suite/data_dir.hpp"
#include "cli.hpp"
#include "core/error.hpp"

namespace revisit {
namespace {

/// argv from strings; the storage outlives the call.
struct Args {
    explicit Args(std::vector<std::string> words) : words(std::move(words)) {
        for (auto& w : this->words) pointers.push_back(w.data());
    }
    std::vector<std::string> Remaining(int argc) const { return {words.begin(), words.begin() + argc}; }
    std::vector<std::string> words;
    std::vector<char*> pointers;
};

/// Sets an environment variable for one scope.
struct ScopedEnv {
    ScopedEnv(const char* name, const char* value) : name(name) {
        if (const char* old = std::getenv(name)) had = true, previous = old;
        if (value) setenv(name, value, 1);
        else unsetenv(name);
    }
    ~ScopedEnv() {
        if (had) setenv(name, previous.c_str(), 1);
        else unsetenv(name);
    }
    const char* name;
    bool had = false;
    std::string previous;
};

TEST(BenchData, FlagsAreTakenOutAndTheRestIsLeftForGoogleBenchmark) {
    const ScopedEnv data("REVISIT_DATA", nullptr), skip("REVISIT_SKIP_MISSING", nullptr);
    Args args({"bench_x", "--benchmark_filter=Tree", "--data", "/d1", "--skip-missing", "--benchmark_repetitions=3"});
    int argc = int(args.pointers.size());
    const auto options = TakeBenchDataOptions(argc, args.pointers.data());
    EXPECT_EQ(options.data_dir, "/d1");
    EXPECT_TRUE(options.skip_missing);
    std::vector<std::string> rest(args.pointers.begin(), args.pointers.begin() + argc);
    EXPECT_EQ(rest, (std::vector<std::string>{"bench_x", "--benchmark_filter=Tree", "--benchmark_repetitions=3"}));

    Args equals({"bench_x", "--data=/d2"});
    argc = 2;
    EXPECT_EQ(TakeBenchDataOptions(argc, equals.pointers.data()).data_dir, "/d2");
    EXPECT_EQ(argc, 1);

    Args dangling({"bench_x", "--data"});
    argc = 2;
    EXPECT_THROW(TakeBenchDataOptions(argc, dangling.pointers.data()), ConfigError);
}

TEST(BenchData, EnvironmentGivesTheDefaultsAndFlagsOverrideIt) {
    const ScopedEnv data("REVISIT_DATA", "/from/env"), skip("REVISIT_SKIP_MISSING", "1");
    Args none({"bench_x"});
    int argc = 1;
    auto options = TakeBenchDataOptions(argc, none.pointers.data());
    EXPECT_EQ(options.data_dir, "/from/env");
    EXPECT_TRUE(options.skip_missing);
    Args flag({"bench_x", "--data", "/from/flag"});
    argc = 3;
    EXPECT_EQ(TakeBenchDataOptions(argc, flag.pointers.data()).data_dir, "/from/flag");
    const ScopedEnv no("REVISIT_SKIP_MISSING", "0");
    EXPECT_FALSE(SkipMissingFromEnvironment());
}

TEST(BenchData, WithoutEnvironmentTheDefaultIsTheSharedDataFolder) {
    const ScopedEnv data("REVISIT_DATA", nullptr);
    EXPECT_EQ(DefaultDataDir().filename(), "data");
    EXPECT_EQ(DefaultDataDir().parent_path().filename(), "shared");
}

TEST(BenchFailures, MissingDataFailsUnlessSkippingWasAskedAndOtherFailuresAlwaysFail) {
    BenchFailures none;
    EXPECT_EQ(none.ExitCode(false), 0);
    EXPECT_EQ(none.Report(false), "");

    BenchFailures missing;
    missing.NoteMissing("BM_OdometryKitti/1/0: /x/kitti00_first16/velodyne absent");
    EXPECT_EQ(missing.ExitCode(false), 2);
    EXPECT_EQ(missing.ExitCode(true), 0);
    const std::string report = missing.Report(false);
    EXPECT_NE(report.find("1 case(s) did not run"), std::string::npos);
    EXPECT_NE(report.find("BM_OdometryKitti/1/0"), std::string::npos);
    EXPECT_NE(report.find("--skip-missing"), std::string::npos);
    EXPECT_NE(missing.Report(true).find("skipped as asked"), std::string::npos);

    BenchFailures failed = missing;
    failed.NoteFailed("BM_RansacPerCandidate/0", "no closure");
    EXPECT_EQ(failed.ExitCode(true), 2);
    EXPECT_NE(failed.Report(true).find("no closure"), std::string::npos);
}

TEST(BenchCommand, MissingDataFolderIsAnErrorUnlessSkipping) {
    const auto failed = test::RunCli("bench --suite tiny --only pose_graph --data /nonexistent/revisit-data");
    EXPECT_EQ(failed.exit_code, 2) << failed.output;
    EXPECT_NE(failed.output.find("/nonexistent/revisit-data"), std::string::npos);
    EXPECT_NE(failed.output.find("--skip-missing"), std::string::npos);
    EXPECT_EQ(failed.output.find("pose_graph/"), std::string::npos) << "it must fail before measuring";

    const auto skipped =
        test::RunCli("bench --suite tiny --only pose_graph --data /nonexistent/revisit-data --skip-missing");
    EXPECT_EQ(skipped.exit_code, 0) << skipped.output;
    EXPECT_NE(skipped.output.find("pose_graph/300 nodes"), std::string::npos);
    EXPECT_NE(skipped.output.find("skipped as asked"), std::string::npos);
}

}  // namespace
}  // namespace revisit
