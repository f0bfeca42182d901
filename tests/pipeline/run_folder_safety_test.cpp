/// Nothing outside the run folder is touched: a report folder that is a link is refused (never
/// emptied), and a run folder that is the dataset, inside it or reaches it through a link is refused.
#include <gtest/gtest.h>

#include <fstream>
#include <set>
#include <string>

#include "cli.hpp"
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

}  // namespace
}  // namespace revisit
