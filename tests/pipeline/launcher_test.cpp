// Start-up (issue 19): `revisit --help` and `--version` are answered by the small launcher without
// loading the commands' ~190 shared libraries; everything else reaches revisit-full unchanged.
#include <gtest/gtest.h>
#include <cstdio>
#include <filesystem>

#include "cli.hpp"

namespace revisit {
namespace {

constexpr const char* kGnuTime = "/usr/bin/time";

/// Peak memory [MiB] of `revisit ARGUMENT` as GNU time reports it (wait4's ru_maxrss). A child forked
/// from this test would count the test's own pages before exec: time is small, so the figure is the CLI's.
double PeakMib(const std::string& argument) {
    const std::string command =
        std::string(kGnuTime) + " -f 'peak_kb=%M' \"" + REVISIT_CLI + "\" " + argument + " 2>&1 >/dev/null";
    FILE* pipe = popen(command.c_str(), "r");
    if (!pipe) return -1.0;
    char buffer[256];
    double kb = -1.0;
    while (std::fgets(buffer, sizeof(buffer), pipe)) std::sscanf(buffer, "peak_kb=%lf", &kb);
    pclose(pipe);
    return kb / 1024.0;
}

TEST(Launcher, HelpAndVersionStayLight) {
    if (!std::filesystem::exists(kGnuTime)) GTEST_SKIP() << kGnuTime << " absent: cannot measure peak memory";
    const double full = PeakMib("info --help");  // reaches revisit-full: every library loaded
    for (const char* argument : {"--help", "--version"}) {
        const double peak = PeakMib(argument);
        EXPECT_GT(peak, 0.0) << argument;
        EXPECT_LT(peak, 20.0) << argument << ": the commands' libraries were loaded";
        EXPECT_LT(peak, 0.5 * full) << argument;
    }
}

TEST(Launcher, HelpIsTheFullBinarysHelp) {
    const auto launcher = test::RunCli("--help");
    const std::filesystem::path full = std::filesystem::path(REVISIT_CLI).parent_path() / "revisit-full";
    ASSERT_TRUE(std::filesystem::exists(full));
    FILE* pipe = popen(("\"" + full.string() + "\" --help 2>&1").c_str(), "r");
    ASSERT_NE(pipe, nullptr);
    std::string expected;
    char buffer[4096];
    while (std::fgets(buffer, sizeof(buffer), pipe)) expected += buffer;
    pclose(pipe);
    EXPECT_EQ(launcher.output, expected);
    for (const char* command : {"run", "demo", "bench", "simulate", "eval"})
        EXPECT_NE(launcher.output.find(command), std::string::npos) << command;
}

TEST(Launcher, OtherCommandsReachTheFullBinaryWithTheirExitCodes) {
    const auto missing = test::RunCli("info");  // a required argument is missing: CLI11's exit code
    EXPECT_NE(missing.exit_code, 0);
    EXPECT_NE(missing.output.find("dataset is required"), std::string::npos) << missing.output;
    const auto sub_help = test::RunCli("run --help");
    EXPECT_EQ(sub_help.exit_code, 0);
    EXPECT_NE(sub_help.output.find("--poses"), std::string::npos);
}

}  // namespace
}  // namespace revisit
