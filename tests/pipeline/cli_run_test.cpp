/// Black-box tests of `revisit run` and friends, as a user runs them.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cstdlib>
#include <fstream>
#include <iterator>

#include "cli.hpp"
#include "read_all.hpp"
#include "test_data.hpp"
#include "config/config.hpp"
#include "io/trajectory_io.hpp"
#include "runfolder/run_files.hpp"
#include "sim_dataset.hpp"

namespace revisit {
namespace {
namespace fs = std::filesystem;
using test::Quote;
using test::RunCli;

TEST(CliRun, EveryCommandHasHelpWithExamples) {
    for (const char* command : {"run", "demo", "simulate", "odometry", "eval", "report", "inspect", "config", "info", "convert", "bench"}) {
        const auto help = RunCli(std::string(command) + " --help");
        EXPECT_EQ(help.exit_code, 0) << command;
        EXPECT_NE(help.output.find("Example"), std::string::npos) << command << ":\n" << help.output;
    }
}

TEST(CliRun, MissingDatasetFailsWithoutCreatingTheRunFolder) {
    test::TempDir dir;
    const auto result = RunCli("run /nonexistent/seq --out " + Quote((dir / "run").string()));
    EXPECT_EQ(result.exit_code, 1);
    EXPECT_NE(result.output.find("/nonexistent/seq: no such file or folder"), std::string::npos) << result.output;
    EXPECT_FALSE(fs::exists(dir / "run"));
}

TEST(CliRun, BadConfigNamesTheKey) {
    const auto result = RunCli("run " + Quote(test::TinySimDataset().string()) + " --set density.resolutoin=0.3");
    EXPECT_EQ(result.exit_code, 1);
    EXPECT_NE(result.output.find("did you mean 'density.resolution'"), std::string::npos) << result.output;
    EXPECT_EQ(RunCli("run x --config no-such-preset").exit_code, 1);
}

TEST(CliRun, RefusesANonEmptyRunFolderUnlessForced) {
    test::TempDir dir;
    const auto out = dir / "run";
    fs::create_directories(out);
    std::ofstream(out / "notes.txt") << "mine";
    const std::string command = "run " + Quote(test::TinySimDataset().string()) + " --to 60 --quiet --set output.write_report=false --out " + Quote(out.string());
    const auto refused = RunCli(command);
    EXPECT_EQ(refused.exit_code, 1);
    EXPECT_NE(refused.output.find("--force"), std::string::npos) << refused.output;
    EXPECT_FALSE(fs::exists(out / "run.json"));
    const auto forced = RunCli(command + " --force");
    EXPECT_EQ(forced.exit_code, 0) << forced.output;
    EXPECT_TRUE(fs::exists(out / "notes.txt"));
    EXPECT_EQ(ReadRunState(RunFolder::Open(out)).odometry.size(), 61u);
}

TEST(CliRun, SimulatedSequenceRunsWithTheDefaults) {
    // The simulated worlds register like real ones (issue 15): no special preset is chosen for them.
    test::TempDir dir;
    const auto run = RunCli("run " + Quote(test::TinySimDataset().string()) + " --to 20 --set output.write_report=false --out " +
                            Quote((dir / "auto").string()));
    ASSERT_EQ(run.exit_code, 0) << run.output;
    EXPECT_EQ(run.output.find("--config sim"), std::string::npos) << run.output;
    // Issue 14: the settings follow from the first scans, are printed with their reasons and kept in config.yaml.
    EXPECT_NE(run.output.find("settings from the data"), std::string::npos) << run.output;
    const fs::path config_file = RunFolder::Open(dir / "auto").config();
    const PipelineConfig config = LoadConfig({config_file.string()}, {});
    EXPECT_GT(config.odometry.voxel_size, 0.0);
    EXPECT_LT(config.odometry.min_range, 5.0);
    std::ifstream in(config_file);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    EXPECT_NE(text.find("# Settings derived from the data"), std::string::npos) << text;
    EXPECT_NE(text.find("odometry.voxel_size = "), std::string::npos) << text;
    // An explicit value wins over the data.
    const auto set = RunCli("run " + Quote(test::TinySimDataset().string()) + " --to 20 --set odometry.voxel_size=0.7 " +
                            "--set output.write_report=false --out " + Quote((dir / "set").string()));
    ASSERT_EQ(set.exit_code, 0) << set.output;
    EXPECT_DOUBLE_EQ(LoadConfig({RunFolder::Open(dir / "set").config().string()}, {}).odometry.voxel_size, 0.7);
}

TEST(CliRun, FromGoesToItsScanInAFolderAndCountsTheScansAStreamDrops) {
    test::TempDir dir;
    // A folder of scan files: the run starts at scan 10 without reading the ones before.
    const auto run = RunCli("run " + Quote(test::TinySimDataset().string()) + " --from 10 --to 20 --set output.write_report=false --out " +
                            Quote((dir / "run").string()));
    ASSERT_EQ(run.exit_code, 0) << run.output;
    EXPECT_EQ(run.output.find("scans skipped"), std::string::npos) << run.output;
    EXPECT_NE(run.output.find("11/11 scans (100%)"), std::string::npos) << run.output;
    const RunState state = ReadRunState(RunFolder::Open(dir / "run"));
    ASSERT_EQ(state.odometry.size(), 11u);
    ASSERT_EQ(state.reference.size(), 11u);
    const auto folder_scans = test::ReadAllScans(test::TinySimDataset());
    ASSERT_GT(folder_scans.size(), 10u);
    ASSERT_TRUE(folder_scans[10].T_world_sensor);
    EXPECT_LT((state.reference.front().translation() - folder_scans[10].T_world_sensor->translation()).norm(), 1e-6);
    // `eval` reads the run's dataset again, from the same scan.
    const auto eval = RunCli("eval " + Quote((dir / "run").string()));
    ASSERT_EQ(eval.exit_code, 0) << eval.output;
    EXPECT_EQ(eval.output.find("scans skipped"), std::string::npos) << eval.output;
    EXPECT_NE(eval.output.find("11/11 scans (evaluation) (100%)"), std::string::npos) << eval.output;
    // A stream (a rawlog) cannot seek: the scans before --from are read and dropped, which on a long
    // recording takes minutes, and the user sees them counted.
    const fs::path rawlog = dir / "walk.rawlog";
    ASSERT_EQ(RunCli("simulate --preset indoor-2d-360 --scans 30 --quiet --out " + Quote(rawlog.string())).exit_code, 0);
    const auto stream = RunCli("run " + Quote(rawlog.string()) + " --from 10 --to 20 --set output.write_report=false --out " +
                               Quote((dir / "stream").string()));
    ASSERT_EQ(stream.exit_code, 0) << stream.output;
    EXPECT_NE(stream.output.find("10/10 scans skipped (100%)"), std::string::npos) << stream.output;
    EXPECT_EQ(ReadRunState(RunFolder::Open(dir / "stream")).odometry.size(), 11u);
    const auto stream_eval = RunCli("eval " + Quote((dir / "stream").string()));
    ASSERT_EQ(stream_eval.exit_code, 0) << stream_eval.output;
    EXPECT_NE(stream_eval.output.find("10/10 scans skipped (100%)"), std::string::npos) << stream_eval.output;
}

TEST(CliRun, InterruptedRunLeavesAValidPartialFolder) {
    test::TempDir dir;
    const auto out = dir / "run";
    // SIGINT 1 s after the run folder appears (the settings from the data come first): the run stops
    // reading, writes what it has and exits with 130.
    // (sh -c '...' around the whole; the paths are double-quoted inside it.)
    const auto dq = [](const std::string& text) { return "\"" + text + "\""; };
    const std::string run = dq(REVISIT_CLI) + " run " + dq(test::TinySimDataset().string()) + " --quiet --out " +
                            dq(out.string()) + " >/dev/null 2>&1";
    const std::string command = "sh -c '" + run + " & pid=$!; i=0; while [ ! -d " + dq(out.string()) +
                                " ] && [ $i -lt 1200 ]; do sleep 0.1; i=$((i+1)); done; sleep 1; kill -INT $pid; wait $pid'";
    const int status = std::system(command.c_str());
    ASSERT_TRUE(WIFEXITED(status));
    EXPECT_EQ(WEXITSTATUS(status), 130);
    const RunState state = ReadRunState(RunFolder::Open(out));
    EXPECT_FALSE(state.complete);
    EXPECT_GT(state.odometry.size(), 0u);
    EXPECT_LT(state.odometry.size(), 1600u);
    EXPECT_EQ(state.corrected.size(), state.odometry.size());
}

TEST(CliRun, ConfigPrintsTheResolvedParameters) {
    const auto result = RunCli("config --config indoor2d --set density.resolution=0.25");
    EXPECT_EQ(result.exit_code, 0);
    EXPECT_NE(result.output.find("planar: true"), std::string::npos);
    EXPECT_NE(result.output.find("resolution: 0.25"), std::string::npos);
}

}  // namespace
}  // namespace revisit

namespace revisit {
namespace {
TEST(CliRun, EvalReportAndInspectRedrawFromTheRunFolder) {
    test::TempDir dir;
    const auto out = (dir / "run").string();
    const auto run = test::RunCli("run " + test::Quote(test::TinySimDataset().string()) +
                                  " --to 300 --quiet --set output.write_report=false --out " + test::Quote(out));
    ASSERT_EQ(run.exit_code, 0) << run.output;
    // `eval` recomputes the run's own figures, byte for byte, from the ground truth the run cached.
    const auto read = [&out](const char* name) { return test::ReadFile(fs::path(out) / name); };
    const std::string metrics = read("metrics.json"), ground_truth = read("ground_truth_closures.txt");
    ASSERT_FALSE(metrics.empty());
    ASSERT_NE(ground_truth.find("\nkey "), std::string::npos);
    const auto eval = test::RunCli("eval " + test::Quote(out) + " --quiet");
    ASSERT_EQ(eval.exit_code, 0) << eval.output;
    EXPECT_EQ(read("ground_truth_closures.txt"), ground_truth);
    EXPECT_EQ(read("metrics.json"), metrics);
    const auto report = test::RunCli("report " + test::Quote(out));
    EXPECT_EQ(report.exit_code, 0) << report.output;
    EXPECT_TRUE(fs::exists(fs::path(out) / "report" / "index.html"));
    // A local map's page on demand, with the keypoints read back from the run's closure database.
    const auto map = test::RunCli("inspect " + test::Quote(out) + " --map 0");
    EXPECT_EQ(map.exit_code, 0) << map.output;
    std::ifstream map_page(fs::path(out) / "report" / "map_0000.html");
    const std::string map_html((std::istreambuf_iterator<char>(map_page)), std::istreambuf_iterator<char>());
    const auto keypoints_at = map_html.find("ORB keypoints</th><td>");
    ASSERT_NE(keypoints_at, std::string::npos) << map_html;
    EXPECT_GT(std::stoi(map_html.substr(keypoints_at + 22)), 0) << map_html;
    const auto pair = test::RunCli("inspect " + test::Quote(out) + " --maps 1 0");
    EXPECT_EQ(pair.exit_code, 0) << pair.output;
    EXPECT_TRUE(fs::exists(fs::path(out) / "report" / "maps_1_0.html"));
    // The pages say RUN_DIR, never the folder itself: a run folder's pages are the same wherever it
    // was written (the index names it once).
    int pages = 0;
    for (const auto& entry : fs::directory_iterator(fs::path(out) / "report")) {
        if (entry.path().extension() != ".html") continue;
        ++pages;
        const std::string html = test::ReadFile(entry.path());
        const bool index = entry.path().filename() == "index.html";
        EXPECT_EQ(html.find(out) != std::string::npos, index) << entry.path();
    }
    EXPECT_GE(pages, 3);  // the index and the two pages rendered on demand
    const auto missing = test::RunCli("inspect " + test::Quote(out) + " --closure 9999");
    EXPECT_EQ(missing.exit_code, 1);
    EXPECT_NE(missing.output.find("no closure 9999"), std::string::npos) << missing.output;
    EXPECT_EQ(test::RunCli("report " + test::Quote((dir / "nothing").string())).exit_code, 1);
    // Templates that cannot be found: an error naming where they were looked for.
    const std::string nowhere = (dir / "no-share").string();
    ASSERT_EQ(setenv("REVISIT_SHARE_DIR", nowhere.c_str(), 1), 0);  // inherited by the command
    const auto no_templates = test::RunCli("report " + test::Quote(out) + " --quiet");
    unsetenv("REVISIT_SHARE_DIR");
    EXPECT_EQ(no_templates.exit_code, 1) << no_templates.output;
    EXPECT_NE(no_templates.output.find(nowhere), std::string::npos) << no_templates.output;
}

TEST(CliRun, PosesPriorTakesTheRecordedOdometryAsItIs) {
    // A drifting prior, used as the trajectory: no registration, the closures alone must correct it.
    test::TempDir dir;
    const fs::path rawlog = dir / "drift.rawlog";
    const auto sim = RunCli("simulate --preset indoor-2d-360 --scans 60 --quiet --odometry-scale-bias 0.05 --out " +
                            Quote(rawlog.string()));
    ASSERT_EQ(sim.exit_code, 0) << sim.output;
    const fs::path out = dir / "run";
    const auto run = RunCli("run " + Quote(rawlog.string()) + " --poses prior --quiet --set output.write_report=false --out " +
                            Quote(out.string()));
    ASSERT_EQ(run.exit_code, 0) << run.output;
    const auto scans = test::ReadAllScans(rawlog);
    const Trajectory written = ReadTumPoses(out / "poses_odometry_tum.txt");
    ASSERT_EQ(written.poses.size(), scans.size());
    ASSERT_TRUE(scans.front().T_odom_sensor);
    double largest = 0.0;
    for (std::size_t k = 0; k < scans.size(); ++k) {
        ASSERT_TRUE(scans[k].T_odom_sensor);
        largest = std::max(largest, (scans[k].T_odom_sensor->translation() - written.poses[k].translation()).norm());
    }
    EXPECT_LT(largest, 1e-6) << "the prior, not a registration, is the trajectory";
    std::ifstream options(out / "run_options.json");
    EXPECT_EQ(nlohmann::json::parse(options).at("poses"), "prior");
    // A dataset without a prior: a named error.
    const fs::path folder = dir / "kitti";
    ASSERT_EQ(RunCli("simulate --preset demo --scans 3 --quiet --out " + Quote(folder.string())).exit_code, 0);
    const auto none = RunCli("run " + Quote(folder.string()) + " --poses prior --quiet --out " + Quote((dir / "none").string()));
    EXPECT_NE(none.exit_code, 0);
    EXPECT_NE(none.output.find("has no odometry prior"), std::string::npos) << none.output;
}

TEST(CliSimulate, StrongOdometryDriftIsWrittenIntoTheRawlogPrior) {
    test::TempDir dir;
    const auto final_error = [](const fs::path& rawlog) {
        const auto scans = test::ReadAllScans(rawlog);
        if (scans.empty() || !scans.back().T_odom_sensor || !scans.back().T_world_sensor) return -1.0;
        // Both start at the first ground-truth pose: the last scan shows the accumulated drift.
        return (scans.back().T_odom_sensor->translation() - scans.back().T_world_sensor->translation()).norm();
    };
    const std::string common = "simulate --preset indoor-2d-360 --scans 80 --quiet --out ";
    const auto plain = RunCli(common + Quote((dir / "plain.rawlog").string()));
    ASSERT_EQ(plain.exit_code, 0) << plain.output;
    const auto strong = RunCli(common + Quote((dir / "strong.rawlog").string()) + " --odometry-scale-bias 0.1 --odometry-yaw-bias 2");
    ASSERT_EQ(strong.exit_code, 0) << strong.output;
    std::ifstream yaml(dir / "strong.rawlog.sim.yaml");
    const std::string text((std::istreambuf_iterator<char>(yaml)), std::istreambuf_iterator<char>());
    EXPECT_NE(text.find("speed_scale_bias: 0.1,"), std::string::npos) << text;
    const double plain_error = final_error(dir / "plain.rawlog"), strong_error = final_error(dir / "strong.rawlog");
    ASSERT_GE(plain_error, 0.0);
    EXPECT_GT(strong_error, 2.0 * plain_error) << plain_error << " m vs " << strong_error << " m";
    // Out of range: a clear error, nothing written.
    const auto bad = RunCli(common + Quote((dir / "bad.rawlog").string()) + " --odometry-scale-bias 0.9");
    EXPECT_NE(bad.exit_code, 0);
    EXPECT_FALSE(fs::exists(dir / "bad.rawlog"));
}
}  // namespace
}  // namespace revisit
