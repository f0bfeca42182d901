/// `revisit run` with reference and pose files that do not match the scans one to one: TUM files
/// pair by time stamp (scans they do not cover are reported and left out of the metrics, or are an
/// error for --poses), KITTI files by index with one pose per scan.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cstdio>
#include <fstream>

#include "cli.hpp"
#include "io/trajectory_io.hpp"
#include "test_data.hpp"

namespace revisit {
namespace {
namespace fs = std::filesystem;
using test::Quote;
using test::RunCli;

/// Scans [first, last] of kitti00_first16 as a TUM file (its times.txt, its poses.txt positions),
/// `shift` [s] added to every time.
void WriteTumOfScans(const fs::path& file, std::size_t first, std::size_t last, double shift = 0.0) {
    const auto dataset = test::SharedData("kitti00_first16");
    const auto times = ReadTimes(dataset / "times.txt");
    const auto poses = ReadKittiPoses(dataset / "poses.txt").poses;
    std::ofstream out(file);
    for (std::size_t i = first; i <= last; ++i) {
        const auto p = poses[i].translation();
        char line[200];
        std::snprintf(line, sizeof line, "%.9f %.9f %.9f %.9f 0 0 0 1\n", times[i] + shift, p.x(), p.y(), p.z());
        out << line;
    }
}

nlohmann::json ReadJson(const fs::path& file) {
    std::ifstream in(file);
    return nlohmann::json::parse(in);
}

TEST(ReferencePairingCli, ScansOutsideATumReferenceAreReportedAndLeftOut) {
    const auto dataset = test::SharedData("kitti00_first16");
    REVISIT_REQUIRE_DATA(dataset);
    test::TempDir dir;
    WriteTumOfScans(dir / "mid.tum", 3, 12);
    const auto r = RunCli("run " + Quote(dataset.string()) + " --poses dataset --gt " + Quote((dir / "mid.tum").string()) +
                          " --out " + Quote((dir / "run").string()) + " --quiet");
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("6 scans have no reference pose"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("first scan 0 at t = 0 s, last scan 15 at t = 1.555212 s"), std::string::npos) << r.output;
    const auto metrics = ReadJson(dir / "run" / "metrics.json");
    EXPECT_EQ(metrics["reference"]["paired_scans"], 10);
    EXPECT_EQ(metrics["trajectory"]["odometry"]["ape_translation_m"]["count"], 10);
    // The run's one local map holds all 16 scans: none lies wholly within the reference, so no closure
    // metrics (partial_reference_test.cpp has a reference covering some maps whole).
    EXPECT_EQ(metrics["reference"]["evaluated_maps"], 0);
    EXPECT_FALSE(metrics.contains("methods"));
    EXPECT_NE(r.output.find("no local map lies wholly within the reference: no closure metrics"), std::string::npos) << r.output;
    const auto info = ReadJson(dir / "run" / "run.json");
    EXPECT_EQ(info["reference_scans"], nlohmann::json({3, 4, 5, 6, 7, 8, 9, 10, 11, 12}));
    // `revisit eval` reads the same pairing back from the run folder.
    const auto again = RunCli("eval " + Quote((dir / "run").string()) + " --quiet");
    EXPECT_EQ(again.exit_code, 0) << again.output;
    EXPECT_NE(again.output.find("reference poses for 10 of 16 scans"), std::string::npos) << again.output;
}

TEST(ReferencePairingCli, PosesFilesPairByTimeOrByIndexWithOnePosePerScan) {
    const auto dataset = test::SharedData("kitti00_first16");
    REVISIT_REQUIRE_DATA(dataset);
    test::TempDir dir;
    const std::string run = " --out " + Quote((dir / "run").string()) + " --quiet --force";
    // A TUM file that ends at scan 10: scan 11 has no pose, the run stops naming it and the span.
    WriteTumOfScans(dir / "first11.tum", 0, 10);
    auto r = RunCli("run " + Quote(dataset.string()) + " --poses " + Quote((dir / "first11.tum").string()) + run);
    EXPECT_NE(r.exit_code, 0);
    EXPECT_NE(r.output.find("scan 11 at t = 1.140497 s is outside the file's poses"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("t = 0 .. 1.03691 s (11 poses"), std::string::npos) << r.output;
    // 19 TUM poses for 16 scans: three more after the last scan, paired by time, not by index.
    {
        WriteTumOfScans(dir / "poses19.tum", 0, 15);
        std::ofstream(dir / "poses19.tum", std::ios::app) << "1.7 0 0 0 0 0 0 1\n1.8 0 0 0 0 0 0 1\n1.9 0 0 0 0 0 0 1\n";
    }
    r = RunCli("run " + Quote(dataset.string()) + " --poses " + Quote((dir / "poses19.tum").string()) + run);
    EXPECT_EQ(r.exit_code, 0) << r.output;
    // KITTI files pair by index: 19 poses for 16 scans is an error naming both counts.
    {
        std::ofstream out(dir / "kitti19.txt");
        out << test::ReadFile(dataset / "poses.txt");
        for (int i = 0; i < 3; ++i) out << "1 0 0 0 0 1 0 0 0 0 1 0\n";
    }
    r = RunCli("run " + Quote(dataset.string()) + " --poses dataset --gt " + Quote((dir / "kitti19.txt").string()) + run);
    EXPECT_NE(r.exit_code, 0);
    EXPECT_NE(r.output.find("--gt has 19 poses for 16 scans"), std::string::npos) << r.output;
    r = RunCli("run " + Quote(dataset.string()) + " --poses " + Quote((dir / "kitti19.txt").string()) + run);
    EXPECT_NE(r.exit_code, 0);
    EXPECT_NE(r.output.find("--poses has 19 poses for 16 scans"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace revisit
