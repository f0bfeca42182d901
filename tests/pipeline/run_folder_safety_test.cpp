/// Nothing outside the run folder is touched: a report folder that is a link is refused (never
/// emptied), and a run folder that is the dataset, inside it or reaches it through a link is refused.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <map>
#include <sstream>
#include <set>
#include <string>

#include <csignal>

#include <nlohmann/json.hpp>

#include "cli.hpp"
#include "pipeline/interrupt.hpp"
#include "pipeline/report_builder.hpp"
#include "sim_dataset.hpp"

namespace revisit {
namespace {
namespace fs = std::filesystem;
using test::Quote;
using test::RunCli;

std::set<std::string> Listing(const fs::path& folder) {
    std::set<std::string> names;
    for (const auto& entry : fs::recursive_directory_iterator(folder)) names.insert(fs::relative(entry.path(), folder).string());
    return names;
}

/// A folder of three small .pcd scans (ASCII, a few hundred points on two walls).
fs::path WritePcdFolder(const fs::path& folder) {
    fs::create_directories(folder);
    for (int s = 0; s < 3; ++s) {
        std::ofstream out(folder / ("scan_" + std::to_string(s) + ".pcd"));
        const int n = 400;
        out << "VERSION .7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\nWIDTH " << n << "\nHEIGHT 1\n"
            << "VIEWPOINT 0 0 0 1 0 0 0\nPOINTS " << n << "\nDATA ascii\n";
        for (int i = 0; i < n; ++i) {
            const double t = 0.05 * (i / 2) - 5.0 + 0.1 * s;
            out << (i % 2 ? t : 5.0) << ' ' << (i % 2 ? 4.0 : t) << ' ' << 0.01 * (i % 7) << '\n';
        }
    }
    return folder;
}

TEST(RunFolderSafety, ARunFolderThatIsTheDatasetOrInsideItIsRefused) {
    test::TempDir dir;
    const fs::path dataset = WritePcdFolder(dir / "scans");
    fs::create_directory_symlink(dataset, dir / "link_to_scans");
    const auto before = Listing(dataset);
    for (const fs::path& out : {dataset, dataset / "run", dir / "link_to_scans", dir / "link_to_scans" / "run"}) {
        const auto result = RunCli("run " + Quote(dataset.string()) + " --quiet --set output.write_report=false --force --out " +
                                   Quote(out.string()));
        EXPECT_EQ(result.exit_code, 1) << out << ":\n" << result.output;
        EXPECT_NE(result.output.find(out.string()), std::string::npos) << result.output;
        EXPECT_NE(result.output.find("input"), std::string::npos) << result.output;
        EXPECT_EQ(Listing(dataset), before) << out;  // nothing written into the dataset
        const auto odometry = RunCli("odometry " + Quote(dataset.string()) + " --quiet --force --out " + Quote(out.string()));
        EXPECT_EQ(odometry.exit_code, 1) << out << ":\n" << odometry.output;
        EXPECT_EQ(Listing(dataset), before) << out;
    }
}

TEST(RunFolderSafety, AReportFolderThatIsALinkIsRefusedAndItsTargetKept) {
    test::TempDir dir;
    const fs::path run = dir / "run";
    const auto result = RunCli("run " + Quote(test::TinySimDataset().string()) +
                               " --to 60 --quiet --set output.write_report=false --out " + Quote(run.string()));
    ASSERT_EQ(result.exit_code, 0) << result.output;
    // Someone else's pictures and pages, reached through report/.
    const fs::path elsewhere = dir / "elsewhere";
    fs::create_directories(elsewhere);
    for (const char* name : {"index.html", "photo.png", "drawing.svg"}) std::ofstream(elsewhere / name) << "mine";
    fs::remove_all(run / "report");
    fs::create_directory_symlink(elsewhere, run / "report");
    const auto before = Listing(elsewhere);
    for (const std::string& command : {"report " + Quote(run.string()), "inspect " + Quote(run.string()) + " --map 0"}) {
        const auto refused = RunCli(command);
        EXPECT_EQ(refused.exit_code, 1) << command << ":\n" << refused.output;
        EXPECT_NE(refused.output.find((run / "report").string()), std::string::npos) << refused.output;
        EXPECT_NE(refused.output.find("symbolic link"), std::string::npos) << refused.output;
        EXPECT_EQ(Listing(elsewhere), before) << command;
        EXPECT_TRUE(test::ReadFile(elsewhere / "index.html") == "mine");  // not a page of the report
    }
    // `run --force` into the folder: refused before a result is written through the link.
    const auto rerun = RunCli("run " + Quote(test::TinySimDataset().string()) +
                              " --to 60 --quiet --force --out " + Quote(run.string()));
    EXPECT_EQ(rerun.exit_code, 1) << rerun.output;
    EXPECT_NE(rerun.output.find((run / "report").string()), std::string::npos) << rerun.output;
    EXPECT_EQ(Listing(elsewhere), before);
    // A real report/ holding a link named like a page: the report is redrawn, the link's target kept.
    fs::remove(run / "report");
    fs::create_directories(run / "report");
    fs::create_symlink(elsewhere / "photo.png", run / "report" / "old.png");
    const auto report = RunCli("report " + Quote(run.string()) + " --quiet");
    ASSERT_EQ(report.exit_code, 0) << report.output;
    EXPECT_TRUE(fs::is_regular_file(fs::symlink_status(run / "report" / "index.html")));
    EXPECT_EQ(Listing(elsewhere), before);
    EXPECT_TRUE(test::ReadFile(elsewhere / "photo.png") == "mine");
}

/// A short run of the tiny simulation with its report, into `run`.
void RunTiny(const fs::path& run, const std::string& extra = "") {
    const auto result = RunCli("run " + Quote(test::TinySimDataset().string()) + " --to 60 --quiet --out " + Quote(run.string()) + extra);
    ASSERT_EQ(result.exit_code, 0) << result.output;
}

std::map<std::string, std::string> Contents(const fs::path& folder) {
    std::map<std::string, std::string> files;
    for (const auto& entry : fs::directory_iterator(folder)) files[entry.path().filename().string()] = test::ReadFile(entry.path());
    return files;
}

TEST(RunFolderSafety, AReportThatFailsOrIsInterruptedLeavesTheOldReport) {
    test::TempDir dir;
    const fs::path run = dir / "run";
    RunTiny(run);
    const auto before = Contents(run / "report");
    ASSERT_GT(before.size(), 3u);
    // A damaged density image: the new report fails, the old one is kept whole and nothing is left beside it.
    const fs::path png = run / "maps" / "map_0000_density.png";
    ASSERT_TRUE(fs::exists(png));
    const std::string good_png = test::ReadFile(png);
    std::ofstream(png, std::ios::trunc) << "not a PNG";
    const auto failed = RunCli("report " + Quote(run.string()) + " --quiet");
    EXPECT_EQ(failed.exit_code, 1) << failed.output;
    EXPECT_EQ(Contents(run / "report"), before);
    for (const auto& entry : fs::directory_iterator(run)) EXPECT_EQ(entry.path().filename().string().rfind(".report", 0), std::string::npos);
    std::ofstream(png, std::ios::trunc | std::ios::binary) << good_png;
    // Ctrl-C: the report stops with Interrupted and the old one stays.
    InstallInterruptHandler();
    std::raise(SIGINT);
    ASSERT_TRUE(InterruptRequested());
    std::ostringstream log;
    EXPECT_THROW(WriteRunReport(RunFolder::Open(run), log, {true, {}}), Interrupted);
    InstallInterruptHandler();  // clears the flag for the other tests
    std::signal(SIGINT, SIG_DFL);
    std::signal(SIGTERM, SIG_DFL);
    EXPECT_EQ(Contents(run / "report"), before);
    // Completed, it replaces the old one.
    const auto redone = RunCli("report " + Quote(run.string()) + " --quiet");
    EXPECT_EQ(redone.exit_code, 0) << redone.output;
    EXPECT_TRUE(fs::is_regular_file(run / "report" / "index.html"));
}

TEST(RunFolderSafety, RunForceRemovesTheResultsOfTheEarlierRun) {
    test::TempDir dir;
    const fs::path run = dir / "run";
    RunTiny(run);
    ASSERT_TRUE(fs::exists(run / "metrics.json"));
    std::ofstream(run / "notes.txt") << "mine";
    // Into the same folder: three PCD scans without a reference (no metrics, one map).
    const fs::path pcd = WritePcdFolder(dir / "scans");
    const auto result = RunCli("run " + Quote(pcd.string()) + " --to 10 --quiet --force --out " + Quote(run.string()));
    ASSERT_EQ(result.exit_code, 0) << result.output;
    // --to past the end is said, not silently clamped.
    EXPECT_NE(result.output.find("--to 10 is past the end: the dataset has 3 scans; the run covers scans 0 .. 2"), std::string::npos)
        << result.output;
    EXPECT_FALSE(fs::exists(run / "metrics.json"));  // the earlier run's metrics are not this run's
    for (const auto& entry : fs::directory_iterator(run)) {
        const std::string name = entry.path().filename().string();
        EXPECT_NE(name.rfind("pr_curve_", 0), 0u) << name;
    }
    const std::string maps = test::ReadFile(run / "local_maps.csv");
    const auto map_rows = static_cast<std::size_t>(std::count(maps.begin(), maps.end(), '\n')) - 1;
    std::size_t map_files = 0;
    for (const auto& entry : fs::directory_iterator(run / "maps")) map_files += entry.path().extension() == ".rvmap";
    EXPECT_EQ(map_files, map_rows);
    EXPECT_EQ(test::ReadFile(run / "notes.txt"), "mine");  // not a file revisit wrote
    const std::string index = test::ReadFile(run / "report" / "index.html");
    EXPECT_NE(index.find("No evaluation in this run"), std::string::npos);
    EXPECT_FALSE(fs::exists(run / "report" / "ape_over_time.svg"));
}

TEST(RunFolderSafety, OdometryForceThatFailsLeavesNoEarlierPoses) {
    test::TempDir dir;
    const fs::path out = dir / "odo";
    fs::create_directories(out);
    std::ofstream(out / "poses_kitti.txt") << "1 0 0 0 0 1 0 0 0 0 1 0\n";  // an earlier odometry's
    std::ofstream(out / "notes.txt") << "mine";
    const fs::path dataset = WritePcdFolder(dir / "scans");
    std::ofstream(dataset / "scan_2.pcd", std::ios::trunc) << "VERSION .7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\n";  // cut short
    const auto result = RunCli("odometry " + Quote(dataset.string()) + " --quiet --force --out " + Quote(out.string()));
    EXPECT_NE(result.exit_code, 0) << result.output;
    EXPECT_NE(result.output.find("scan_2.pcd"), std::string::npos) << result.output;
    EXPECT_FALSE(fs::exists(out / "poses_kitti.txt")) << "the earlier poses would pass as this run's";
    EXPECT_EQ(test::ReadFile(out / "notes.txt"), "mine");
}

TEST(RunFolderSafety, ADatasetPathThatIsNotUtf8Runs) {
    test::TempDir dir;
    const fs::path dataset = WritePcdFolder(dir / "caf\xe9 scans");  // Latin-1: not UTF-8
    const fs::path run = dir / "run";
    const auto result = RunCli("run " + Quote(dataset.string()) + " --quiet --out " + Quote(run.string()));
    ASSERT_EQ(result.exit_code, 0) << result.output;
    const auto options = nlohmann::json::parse(test::ReadFile(run / "run_options.json"));
    EXPECT_TRUE(options.contains("dataset_bytes")) << options.dump(2);
    const auto report = RunCli("report " + Quote(run.string()) + " --quiet");
    EXPECT_EQ(report.exit_code, 0) << report.output;
}

}  // namespace
}  // namespace revisit
