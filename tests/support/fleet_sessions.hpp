#pragma once
/// Short sessions for the multi-session tests: one simulated 'tiny' city drive
/// of 330 scans cut into two overlapping sessions (scans 0-199 and 110-329: about 80 m driven twice), and
/// 70 scans of another city (seed 2) that shares no place with them.
#include <filesystem>

#include "cli.hpp"
#include "sim/presets.hpp"
#include "sim/simulate.hpp"
#include "test_data.hpp"

namespace revisit::test {

/// Each piece is made on first use (ctest runs every test in its own process: a test pays only for what it uses).
class FleetSessions {
  public:
    const TempDir& dir() const { return dir_; }
    /// The 330-scan drive.
    const std::filesystem::path& City() {
        if (city_.empty()) {
            SimConfig config = SimPreset("tiny");
            config.max_scans = 330;
            RunSimulation(config, dir_ / "city", true);
            city_ = dir_ / "city";
        }
        return city_;
    }
    /// 70 scans of another world.
    const std::filesystem::path& Elsewhere() {
        if (elsewhere_.empty()) {
            SimConfig config = SimPreset("tiny");
            config.seed = 2;
            config.max_scans = 70;
            RunSimulation(config, dir_ / "world2", true);
            elsewhere_ = dir_ / "world2";
        }
        return elsewhere_;
    }
    /// City scans 0-199.
    const std::filesystem::path& RunA() {
        if (run_a_.empty()) Run("run " + Quote(City().string()) + " --to 199", run_a_ = dir_ / "run_a");
        return run_a_;
    }
    /// City scans 110-329, run with --against RunA().
    const std::filesystem::path& RunB() {
        if (run_b_.empty()) {
            const std::string a = RunA().string();
            run_b_result_ = Run("run " + Quote(City().string()) + " --from 110 --against " + Quote(a), run_b_ = dir_ / "run_b");
        }
        return run_b_;
    }
    const CliResult& RunBResult() {
        RunB();
        return run_b_result_;
    }
    /// All of Elsewhere().
    const std::filesystem::path& RunC() {
        if (run_c_.empty()) Run("run " + Quote(Elsewhere().string()), run_c_ = dir_ / "run_c");
        return run_c_;
    }

  private:
    static CliResult Run(const std::string& command, const std::filesystem::path& out) {
        return RunCli(command + " --out " + Quote(out.string()) + " --quiet --set output.write_report=false --threads 2");
    }
    TempDir dir_;
    std::filesystem::path city_, elsewhere_, run_a_, run_b_, run_c_;
    CliResult run_b_result_;
};

inline FleetSessions& Fleet() {
    static FleetSessions sessions;
    return sessions;
}

}  // namespace revisit::test
