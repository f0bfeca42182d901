/// The whole chain on a simulated drive with a revisit and on a real 2D laser log.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <fstream>
#include <tbb/global_control.h>
#include <sstream>

#include "closures/database_io.hpp"
#include "io/cloud_files.hpp"
#include "io/trajectory_io.hpp"
#include "pipeline/evaluate.hpp"
#include "pipeline/pipeline.hpp"
#include "pipeline/report_builder.hpp"
#include "runfolder/run_files.hpp"
#include "pipeline_run.hpp"
#include "sim_dataset.hpp"

namespace revisit {
namespace {
namespace fs = std::filesystem;

/// Every file of the run folder parses with the project's own readers.
void ExpectParseableRunFolder(const RunFolder& run, const PipelineConfig& config, const RunState& written) {
    const RunState read = ReadRunState(run);
    EXPECT_EQ(read.odometry.size(), written.odometry.size());
    EXPECT_EQ(read.maps.size(), written.maps.size());
    EXPECT_EQ(read.closures.size(), written.closures.size());
    EXPECT_EQ(read.NumAccepted(), written.NumAccepted());
    EXPECT_EQ(ReadKittiPoses(run.corrected_kitti()).size(), written.corrected.size());
    EXPECT_EQ(ReadTumPoses(run.odometry_tum()).size(), written.odometry.size());
    EXPECT_EQ(DumpConfig(LoadConfig({run.config().string()}, {})), DumpConfig(config));
    EXPECT_GT(LoadPly(run.corrected_map()).points.size(), 1000u);
    EXPECT_EQ(LoadDatabase(run.database(), config.detector).maps().size(), written.maps.size());
    std::ifstream timings(run.timings_json());
    EXPECT_FALSE(nlohmann::json::parse(timings, nullptr, false).is_discarded());
}

/// The simulator's ground truth with a smooth drift (1% scale, 1 deg per 100 m of yaw), as a
/// wheel odometry or a weaker LiDAR odometry would give: the closures must take most of it out.
Poses DriftedGroundTruth(const fs::path& dataset) {
    const Poses truth = ReadKittiPoses(dataset / "poses.txt").poses;
    Poses drifted{truth.front()};
    for (std::size_t i = 1; i < truth.size(); ++i) {
        Eigen::Isometry3d step = truth[i - 1].inverse() * truth[i];
        const double length = step.translation().norm();
        step.translation() *= 1.01;
        step.linear() = Eigen::AngleAxisd(length * 0.01 * M_PI / 180.0, Eigen::Vector3d::UnitZ()) * step.linear();
        drifted.push_back(drifted.back() * step);
    }
    return drifted;
}

RunState RunAndEvaluate(const RunOptions& options, const PipelineConfig& config, std::optional<RunEvaluation>& evaluation) {
    std::ostringstream log;
    const RunState state = RunPipeline(options, config, log);
    evaluation = EvaluateRun(RunFolder(options.out), state, options, config, log);
    return state;
}

TEST(EndToEnd, SimulatedDriveWithDriftingOdometryIsCorrected) {
    test::TempDir out;
    RunOptions options;
    options.dataset = test::TinySimDataset();
    options.out = out / "run";
    options.quiet = true;
    options.poses = PoseSource::kFile;
    options.poses_file = out / "drifted.txt";
    WriteKittiPoses(options.poses_file, DriftedGroundTruth(options.dataset));
    const PipelineConfig config;
    std::optional<RunEvaluation> evaluation;
    const RunState state = RunAndEvaluate(options, config, evaluation);
    ASSERT_TRUE(state.complete);
    EXPECT_EQ(state.odometry.size(), 1600u);
    EXPECT_GE(state.NumAccepted(), 2u);
    const RunFolder run(options.out);
    ExpectParseableRunFolder(run, config, state);

    ASSERT_TRUE(evaluation);
    const double before = evaluation->odometry.ape.errors.translation_stats.rmse;
    const double after = evaluation->corrected.ape.errors.translation_stats.rmse;
    EXPECT_GT(before, 5.0);
    EXPECT_LT(after, 0.5 * before) << "APE " << before << " m -> " << after << " m";
    EXPECT_GT(evaluation->gt_scan_pairs, 0u);
    EXPECT_DOUBLE_EQ(evaluation->map_metrics.fraction_right, 1.0);  // every accepted closure joins overlapping maps
    std::ifstream metrics(run.metrics_json());
    const auto json = nlohmann::json::parse(metrics);
    EXPECT_EQ(json["methods"][0]["method"], "density maps");
    EXPECT_TRUE(fs::exists(run.root() / "pr_curve_density.csv"));

    // The report draws from the run folder alone.
    std::ostringstream log;
    WriteRunReport(run, log);
    EXPECT_TRUE(fs::exists(run.report_index()));
    EXPECT_TRUE(fs::exists(run.report_dir() / "closure_0000.html"));
}

TEST(EndToEnd, SimulatedDriveWithOurOdometryFindsOnlyRightClosures) {
    test::TempDir out;
    RunOptions options;
    options.dataset = test::TinySimDataset();
    options.out = out / "run";
    options.quiet = true;
    const PipelineConfig config;
    std::optional<RunEvaluation> evaluation;
    const RunState state = RunAndEvaluate(options, config, evaluation);
    EXPECT_GE(state.NumAccepted(), 1u);
    ASSERT_TRUE(evaluation);
    EXPECT_DOUBLE_EQ(evaluation->map_metrics.fraction_right, 1.0);
    EXPECT_LT(evaluation->map_metrics.translation_error.max, 0.5);  // [m] refined poses against ground truth
}

/// Issue 19: the odometry of a scan runs while the closure pipeline takes the scans before it (two
/// stages on the TBB threads). Each stage sees the scans in order: the run is the same at any thread
/// count, the one-thread run being the plain loop.
TEST(EndToEnd, TheOverlappedStagesGiveTheSameRunAtAnyThreadCount) {
    const PipelineConfig config;
    std::vector<RunState> runs;
    for (const int threads : {1, 2}) {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, std::size_t(threads));
        runs.push_back(test::RunQuietly(test::TinySimDataset(), config));
    }
    ASSERT_GE(runs[0].NumAccepted(), 1u);
    for (std::size_t r = 1; r < runs.size(); ++r) {
        ASSERT_EQ(runs[r].odometry.size(), runs[0].odometry.size());
        for (std::size_t i = 0; i < runs[0].odometry.size(); ++i) {
            ASSERT_TRUE(runs[r].odometry[i].matrix() == runs[0].odometry[i].matrix()) << "scan " << i;
            ASSERT_TRUE(runs[r].corrected[i].matrix() == runs[0].corrected[i].matrix()) << "scan " << i;
        }
        ASSERT_EQ(runs[r].closures.size(), runs[0].closures.size());
        for (std::size_t k = 0; k < runs[0].closures.size(); ++k) {
            const ClosureRecord& a = runs[0].closures[k];
            const ClosureRecord& b = runs[r].closures[k];
            EXPECT_EQ(b.closure.query_id, a.closure.query_id);
            EXPECT_EQ(b.closure.ref_id, a.closure.ref_id);
            EXPECT_EQ(b.accepted, a.accepted);
            EXPECT_TRUE(b.refinement.T_query_ref.matrix() == a.refinement.T_query_ref.matrix());
        }
    }
}

TEST(EndToEnd, RealRadishLogFindsClosures) {
    const auto log_file = test::SharedData("radish/fr079.rawlog");
    REVISIT_REQUIRE_DATA(log_file);
    test::TempDir out;
    RunOptions options;
    options.dataset = log_file;
    options.out = out / "run";
    options.quiet = true;
    options.to = 2999;  // the first 3000 scans revisit the corridors several times
    const PipelineConfig config = LoadConfig({(fs::path(REVISIT_SOURCE_DIR) / "configs/indoor2d.yaml").string()}, {});
    std::ostringstream log;
    const RunState state = RunPipeline(options, config, log);
    EXPECT_EQ(state.odometry.size(), 3000u);
    EXPECT_FALSE(state.has_reference());
    EXPECT_GE(state.NumAccepted(), 3u) << log.str();
    ExpectParseableRunFolder(RunFolder(options.out), config, state);
}

/// Issue 5: the detector beyond the paper against the published detector settings, on the same local
/// maps of a real log (same odometry, maps and pixels: configs/paper-detector.yaml layered after
/// indoor2d). There is no ground truth: the pose graph judges, and rejects closures it finds
/// inconsistent with the odometry and the other closures (graph.min_weight).
TEST(EndToEnd, RealRadishRobustDetectorFindsMoreConsistentClosuresThanThePaperSettings) {
    const auto log_file = test::SharedData("radish/intel.rawlog");
    REVISIT_REQUIRE_DATA(log_file);
    const fs::path configs = fs::path(REVISIT_SOURCE_DIR) / "configs";
    // The detectors are compared: the proximity pass (registrations from the corrected poses, whichever
    // detector found the closures) is off for both.
    const std::vector<std::string> overrides{"input.laser_aperture_deg=180", "output.write_report=false", "proximity.enabled=false"};
    std::size_t accepted[2] = {0, 0}, verified[2] = {0, 0}, maps[2] = {0, 0};
    for (int paper = 0; paper < 2; ++paper) {
        std::vector<std::string> files{(configs / "indoor2d.yaml").string()};
        if (paper) files.push_back((configs / "paper-detector.yaml").string());
        const PipelineConfig config = LoadConfig(files, overrides);
        const RunState state = test::RunQuietly(log_file, config);
        accepted[paper] = state.NumAccepted();
        maps[paper] = state.maps.size();
        for (const auto& record : state.closures) {
            verified[paper] += record.refined && record.refinement.accepted ? 1 : 0;
            if (record.accepted) {
                EXPECT_GE(record.graph_weight, config.graph_noise.min_weight);
            } else if (record.reason.find("inconsistent with the pose graph") != std::string::npos) {
                EXPECT_LT(record.graph_weight, config.graph_noise.min_weight);
            }
        }
    }
    EXPECT_EQ(maps[0], maps[1]);
    // Measured with the prior's bias removed (2026-12-01): 34 of 34 verified stay consistent, against the
    // paper's 6 of 6 (before, with the prior as it comes: 17 of 17 against 6 of 7); at 0.5 m pixels the
    // paper finds none.
    EXPECT_GE(10 * accepted[0], 9 * verified[0]);
    EXPECT_GE(accepted[0], 2 * accepted[1]);
    EXPECT_GE(accepted[0], 12u);
}

}  // namespace
}  // namespace revisit
