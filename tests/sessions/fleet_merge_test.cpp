// revisit merge and revisit run --against on short simulated sessions (tests/pipeline/fleet_sessions.hpp).
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "test_data.hpp"
#include "fleet_sessions.hpp"

namespace revisit {
namespace {
namespace fs = std::filesystem;
using test::Quote;
using test::RunCli;

nlohmann::json Sessions(const fs::path& merge) { return nlohmann::json::parse(test::ReadFile(merge / "sessions.json")); }

TEST(Merge, RunAgainstJoinsTheNewSessionAndMergeGivesTheSameInAnyOrder) {
    auto& fleet = test::Fleet();
    const fs::path run_a = fleet.RunA(), run_b = fleet.RunB();
    ASSERT_EQ(fleet.RunBResult().exit_code, 0) << fleet.RunBResult().output;
    const auto sessions = Sessions(run_b / "merge");
    EXPECT_EQ(sessions["connected_sessions"], 2);
    EXPECT_GE(sessions["cross_closures"]["accepted"].get<int>(), 1);
    EXPECT_EQ(sessions["sessions"][0]["run"], fs::absolute(run_a).lexically_normal().string());
    // Both sessions are in the frame of the first: where they drove the same street (scans 110-199), the
    // second session's trajectory lies on the first's.
    std::ifstream a(run_b / "merge" / "session_00_poses_kitti.txt"), b(run_b / "merge" / "session_01_poses_kitti.txt");
    std::vector<Eigen::Vector3d> first, second;
    for (std::string line; std::getline(a, line);) {
        std::istringstream f(line);
        double v[12];
        for (double& x : v) f >> x;
        first.emplace_back(v[3], v[7], v[11]);
    }
    for (std::string line; std::getline(b, line);) {
        std::istringstream f(line);
        double v[12];
        for (double& x : v) f >> x;
        second.emplace_back(v[3], v[7], v[11]);
    }
    ASSERT_EQ(first.size(), 200u);
    ASSERT_EQ(second.size(), 220u);
    for (std::size_t scan : {130, 160, 190}) EXPECT_LT((first[scan] - second[scan - 110]).norm(), 0.5) << "scan " << scan;
    EXPECT_TRUE(fs::exists(run_b / "merge" / "map_joint.ply"));
    // With a reference, each session's APE in the common frame is reported.
    EXPECT_TRUE(sessions["sessions"][1]["ape_common_m"].is_number());

    // revisit merge, the folders in either order: the same files, the same as --against.
    const fs::path one = fleet.dir() / "merge_ab", two = fleet.dir() / "merge_ba";
    const auto ab = RunCli("merge " + Quote(run_a.string()) + " " + Quote(run_b.string()) + " --out " + Quote(one.string()));
    const auto ba = RunCli("merge " + Quote(run_b.string()) + " " + Quote(run_a.string()) + " --out " + Quote(two.string()));
    ASSERT_EQ(ab.exit_code, 0) << ab.output;
    ASSERT_EQ(ba.exit_code, 0) << ba.output;
    for (const char* file : {"sessions.json", "cross_closures.csv", "session_00_poses_kitti.txt", "session_01_poses_tum.txt"})
        EXPECT_EQ(test::ReadFile(one / file), test::ReadFile(two / file)) << file;
    EXPECT_EQ(test::ReadFile(one / "sessions.json"), test::ReadFile(run_b / "merge" / "sessions.json"));
    // The merge's page: both sessions in their colours, connected, and the cross closures.
    const std::string page = test::ReadFile(one / "index.html");
    EXPECT_EQ(page, test::ReadFile(two / "index.html"));
    EXPECT_NE(page.find("sessions.svg"), std::string::npos);
    EXPECT_NE(page.find("Cross-session closures"), std::string::npos);
    EXPECT_EQ(page.find(">NO<"), std::string::npos) << "both sessions are connected";
}

TEST(Merge, UnconnectedSessionsAndMissingOrCorruptRunsAreReported) {
    auto& fleet = test::Fleet();
    const fs::path run_a = fleet.RunA(), run_c = fleet.RunC();
    const fs::path out = fleet.dir() / "merge_ac";
    // --force into an earlier merge of more sessions: its trajectories must not pass as this merge's.
    fs::create_directories(out);
    for (const char* stale : {"session_01_poses_kitti.txt", "session_07_poses_tum.txt", "sessions.json"})
        std::ofstream(out / stale) << "an earlier merge";
    std::ofstream(out / "notes.txt") << "mine";
    const auto result = RunCli("merge " + Quote(run_c.string()) + " " + Quote(run_a.string()) + " --force --out " +
                               Quote(out.string()));
    EXPECT_EQ(result.exit_code, 3) << result.output;
    EXPECT_NE(result.output.find("has no cross-session closure tying it to the anchor"), std::string::npos) << result.output;
    const auto sessions = Sessions(out);
    EXPECT_EQ(sessions["connected_sessions"], 1);
    EXPECT_EQ(sessions["sessions"][1]["connected"], false);
    EXPECT_EQ(sessions["sessions"][1]["run"], fs::absolute(run_c).lexically_normal().string());
    EXPECT_FALSE(fs::exists(out / "session_01_poses_kitti.txt"));  // never placed at the origin
    EXPECT_TRUE(fs::exists(out / "session_00_poses_kitti.txt"));
    EXPECT_FALSE(fs::exists(out / "session_07_poses_tum.txt"));
    EXPECT_EQ(test::ReadFile(out / "notes.txt"), "mine");  // not a file revisit wrote

    const fs::path missing = fleet.dir() / "no_such_run";
    const auto absent = RunCli("merge " + Quote(run_a.string()) + " " + Quote(missing.string()) + " --out " +
                               Quote((fleet.dir() / "merge_missing").string()));
    EXPECT_EQ(absent.exit_code, 1);
    EXPECT_NE(absent.output.find(missing.string()), std::string::npos) << absent.output;
    EXPECT_NE(absent.output.find("no such run folder"), std::string::npos) << absent.output;

    const fs::path broken = fleet.dir() / "broken_run";
    fs::copy(run_c, broken, fs::copy_options::recursive);
    fs::resize_file(broken / "database.bin", fs::file_size(broken / "database.bin") / 2);
    const auto corrupt = RunCli("merge " + Quote(run_a.string()) + " " + Quote(broken.string()) + " --out " +
                                Quote((fleet.dir() / "merge_corrupt").string()));
    EXPECT_EQ(corrupt.exit_code, 1);
    EXPECT_NE(corrupt.output.find((broken / "database.bin").string()), std::string::npos) << corrupt.output;

    // An interrupted run (complete = false) is refused, naming it, unless --allow-incomplete.
    const fs::path partial = fleet.dir() / "partial_run";
    fs::copy(run_c, partial, fs::copy_options::recursive);
    {
        auto info = nlohmann::json::parse(test::ReadFile(partial / "run.json"));
        info["complete"] = false;
        std::ofstream(partial / "run.json", std::ios::trunc) << info.dump(2);
    }
    const std::string merge_partial = "merge " + Quote(run_a.string()) + " " + Quote(partial.string()) + " --out ";
    const auto refused = RunCli(merge_partial + Quote((fleet.dir() / "merge_partial").string()));
    EXPECT_EQ(refused.exit_code, 1) << refused.output;
    EXPECT_NE(refused.output.find(partial.string() + ": is an interrupted run"), std::string::npos) << refused.output;
    EXPECT_NE(refused.output.find("--allow-incomplete"), std::string::npos) << refused.output;
    EXPECT_FALSE(fs::exists(fleet.dir() / "merge_partial"));
    const auto allowed = RunCli(merge_partial + Quote((fleet.dir() / "merge_partial").string()) + " --allow-incomplete");
    EXPECT_EQ(allowed.exit_code, 3) << allowed.output;  // merged (C is not tied to A, as above)
    EXPECT_NE(allowed.output.find("warning: " + partial.string() + ": is an interrupted run"), std::string::npos) << allowed.output;
    const auto against_partial = RunCli("run " + Quote(fleet.Elsewhere().string()) + " --quiet --out " +
                                        Quote((fleet.dir() / "run_never2").string()) + " --against " + Quote(partial.string()));
    EXPECT_EQ(against_partial.exit_code, 1) << against_partial.output;
    EXPECT_NE(against_partial.output.find("--allow-incomplete"), std::string::npos) << against_partial.output;
    EXPECT_FALSE(fs::exists(fleet.dir() / "run_never2"));

    // --against checks the earlier runs before reading a single scan: nothing is written.
    const fs::path never = fleet.dir() / "run_never";
    const auto against = RunCli("run " + Quote(fleet.Elsewhere().string()) + " --quiet --out " + Quote(never.string()) +
                                " --against " + Quote(missing.string()));
    EXPECT_EQ(against.exit_code, 1);
    EXPECT_NE(against.output.find(missing.string() + ": no such run folder"), std::string::npos) << against.output;
    EXPECT_FALSE(fs::exists(never));
}

}  // namespace
}  // namespace revisit
