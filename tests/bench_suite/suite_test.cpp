// The tiny suite end to end (a few seconds): every group yields finite figures with the right counts,
// real-data cases appear exactly when the data does, and bad names are refused.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "bench_suite/suite.hpp"
#include "core/error.hpp"

namespace revisit {
namespace {

const std::filesystem::path kData = std::filesystem::path(REVISIT_SHARED_DIR) / "data";

bool Has(const BenchRecord& r, const std::string& prefix) {
    for (const auto& m : r.results)
        if (m.name.rfind(prefix, 0) == 0) return true;
    return false;
}

const BenchRecord& TinyRecord() {
    static const BenchRecord record = [] {
        BenchOptions options;
        options.suite = "tiny";
        options.data_dir = kData;
        return RunSuite(options);
    }();
    return record;
}

TEST(Suite, TinyRunsEveryGroupWithFiniteFigures) {
    const auto& r = TinyRecord();
    EXPECT_EQ(r.suite, "tiny");
    EXPECT_GT(r.machine.cores, 0u);
    EXPECT_FALSE(r.machine.build_type.empty());
    EXPECT_GT(r.peak_memory_kb, 0u);
    EXPECT_GT(r.duration_s, 0.0);
    // Every group ran, or (bag_reader: only real data) said why not.
    const auto ran_or_said_why = [&](const std::string& prefix) {
        if (Has(r, prefix)) return true;
        for (const auto& reason : r.skipped)
            if (reason.rfind(prefix, 0) == 0) return true;
        return false;
    };
    for (const auto& group : CaseGroupNames()) EXPECT_TRUE(ran_or_said_why(group + "/")) << group;
    for (const char* name :
         {"odometry/sim 64-beam 1t", "odometry/sim 64-beam 2t", "odometry/sim livox 1t", "odometry/sim 2d 2t",
          "tree/query+insert 10 maps", "tree/query+insert 30 maps", "pose_graph/300 nodes x 10 closures",
          "end_to_end/run scans", "end_to_end/peak memory", "end_to_end/stage odometry"})
        EXPECT_TRUE(Has(r, name)) << name;
    const auto repetitions = std::size_t(ScaleOf("tiny").repeat.repetitions);
    for (const auto& m : r.results) {
        EXPECT_TRUE(std::isfinite(m.median)) << m.name;
        EXPECT_GE(m.median, 0.0) << m.name;
        EXPECT_LE(m.min, m.median) << m.name;
        EXPECT_LE(m.median, m.max) << m.name;
        EXPECT_FALSE(m.note.empty()) << m.name;
        if (m.name.rfind("odometry/", 0) == 0 || m.name.rfind("closures/", 0) == 0) {
            EXPECT_EQ(m.samples.size(), repetitions) << m.name;
        }
        // Stages that do real work on real-sized data never take zero time.
        if (m.name.rfind("odometry/sim 64", 0) == 0 || m.name.rfind("closures/ORB", 0) == 0) {
            EXPECT_GT(m.median, 0.0) << m.name;
        }
    }
    // The 12-scan end-to-end run processed scans and stayed within a sane memory bound.
    for (const auto& m : r.results) {
        if (m.name == "end_to_end/run scans") {
            EXPECT_GT(m.median, 0.0);
        }
        if (m.name == "end_to_end/peak memory") {
            EXPECT_GT(m.median, 10.0);
            EXPECT_LT(m.median, 4096.0);
        }
    }
}

TEST(Suite, RealDataCasesOnlyWhenTheDataExists) {
    if (!std::filesystem::exists(REVISIT_SHARED_DIR)) GTEST_SKIP() << "shared data absent: only the absent case runs";
    const auto& r = TinyRecord();
    EXPECT_TRUE(Has(r, "reader/kitti00_first16"));
    EXPECT_TRUE(Has(r, "odometry/kitti00 64-beam 1t"));
    EXPECT_TRUE(Has(r, "closures/ORB kitti00"));
    EXPECT_EQ(r.data_dir, kData.string());
}

TEST(Suite, AbsentDataIsSkippedWithAReason) {
    BenchOptions options;
    options.suite = "tiny";
    options.data_dir = "/nonexistent/revisit-data";
    options.groups = {"odometry"};
    std::vector<std::string> seen;
    options.progress = [&](const std::string& g) { seen.push_back(g); };
    const auto r = RunSuite(options);
    EXPECT_EQ(seen, std::vector<std::string>{"odometry"});
    EXPECT_TRUE(Has(r, "odometry/sim 64-beam"));
    EXPECT_FALSE(Has(r, "odometry/kitti00"));
    EXPECT_FALSE(Has(r, "reader/"));
    EXPECT_TRUE(r.data_dir.empty());
    ASSERT_FALSE(r.skipped.empty());
    EXPECT_NE(r.skipped.front().find("/nonexistent/revisit-data"), std::string::npos);
}

TEST(Suite, UnknownNamesAreRefused) {
    EXPECT_THROW(ScaleOf("huge"), ConfigError);
    BenchOptions options;
    options.suite = "tiny";
    options.groups = {"odometry", "warp drive"};
    EXPECT_THROW(RunSuite(options), ConfigError);
}

TEST(Suite, QuickAndFullCoverTheIssueSizes) {
    const auto quick = ScaleOf("quick"), full = ScaleOf("full");
    EXPECT_EQ(full.database_sizes.front(), 10);
    EXPECT_EQ(full.database_sizes.back(), 50000);
    EXPECT_GE(full.graph_grid.size(), 4u);
    EXPECT_EQ(full.end_to_end_scans, 0u);  // the whole route, with its revisits
    EXPECT_GT(quick.end_to_end_scans, 0u);
    EXPECT_GE(full.repeat.repetitions, quick.repeat.repetitions);
}

}  // namespace
}  // namespace revisit
