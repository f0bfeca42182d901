#include <gtest/gtest.h>

#include <tbb/global_control.h>

#include <filesystem>
#include <fstream>
#include <iterator>

#include "test_data.hpp"
#include "io/writer.hpp"
#include "sim/presets.hpp"

namespace revisit {
namespace {

/// Keeps every scan in memory.
class MemoryWriter : public DatasetWriter {
  public:
    void Write(const Scan& scan) override { scans.push_back(scan); }
    void Finish() override { finished = true; }
    std::vector<Scan> scans;
    bool finished = false;
};

SimConfig Small(std::uint64_t seed) {
    SimConfig config = SimPreset("tiny");
    config.seed = seed;
    config.max_scans = 6;
    return config;
}

bool SameScans(const std::vector<Scan>& a, const std::vector<Scan>& b) {
    if (a.size() != b.size()) return false;
    for (std::size_t i = 0; i < a.size(); ++i) {
        if (a[i].points.size() != b[i].points.size()) return false;
        for (std::size_t k = 0; k < a[i].points.size(); ++k)
            if (a[i].points[k] != b[i].points[k] || a[i].intensities[k] != b[i].intensities[k]) return false;
        if (!a[i].T_world_sensor->isApprox(*b[i].T_world_sensor, 0.0)) return false;
    }
    return true;
}

TEST(Determinism, SameSeedSameScansWithOneOrTwoThreads) {
    MemoryWriter one, two, other;
    {
        tbb::global_control single(tbb::global_control::max_allowed_parallelism, 1);
        SimulateSequence(Small(3), one);
    }
    SimulateSequence(Small(3), two);
    SimulateSequence(Small(4), other);
    ASSERT_EQ(one.scans.size(), 6u);
    EXPECT_TRUE(one.finished);
    EXPECT_TRUE(SameScans(one.scans, two.scans));
    EXPECT_FALSE(SameScans(one.scans, other.scans));
    for (const auto& scan : one.scans) {
        EXPECT_TRUE(scan.T_world_sensor.has_value());
        EXPECT_TRUE(scan.T_odom_sensor.has_value());
        EXPECT_GT(scan.points.size(), 5000u);
    }
}

TEST(Determinism, SameSeedByteIdenticalKittiFolders) {
    const auto root = std::filesystem::temp_directory_path() / ("revisit_sim_determinism_" + std::to_string(::getpid()));
    std::filesystem::remove_all(root);
    RunSimulation(Small(9), root / "a", false);
    RunSimulation(Small(9), root / "b", false);
    std::size_t files = 0;
    for (const auto& entry : std::filesystem::recursive_directory_iterator(root / "a")) {
        if (!entry.is_regular_file()) continue;
        const auto relative = std::filesystem::relative(entry.path(), root / "a");
        ASSERT_TRUE(std::filesystem::exists(root / "b" / relative)) << relative;
        EXPECT_EQ(test::ReadFile(entry.path()), test::ReadFile(root / "b" / relative)) << relative;
        ++files;
    }
    EXPECT_GE(files, 6u + 3u);  // scans, poses, times (+ calib, sim.yaml)
    EXPECT_TRUE(std::filesystem::exists(root / "a" / "sim.yaml"));
    EXPECT_TRUE(std::filesystem::exists(root / "a" / "poses.txt"));
    std::filesystem::remove_all(root);
}

}  // namespace
}  // namespace revisit
