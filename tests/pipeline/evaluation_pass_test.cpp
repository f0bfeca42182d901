/// The evaluation's share of each scan made during the chain's pass (EvaluationPass): the same
/// evaluation as a second pass over the data, and nothing left in the run folder.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>

#include "pipeline/evaluate.hpp"
#include "pipeline/pipeline.hpp"
#include "pipeline_run.hpp"
#include "runfolder/run_files.hpp"
#include "sim_dataset.hpp"

namespace revisit {
namespace {
namespace fs = std::filesystem;

std::string Contents(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

std::size_t ScratchFiles(const fs::path& folder) {
    std::size_t count = 0;
    for (const auto& entry : fs::directory_iterator(folder)) count += entry.path().filename().string().find("scratch") != std::string::npos;
    return count;
}

TEST(EvaluationPass, GivesTheEvaluationOfASecondPassOverTheData) {
    test::TempDir out;
    RunOptions options = test::QuietRunOptions(test::TinySimDataset(), out / "run");
    const PipelineConfig config;
    std::ostringstream log;
    std::unique_ptr<EvaluationPass> pass;
    const RunState state = RunPipeline(options, config, log, &pass);
    ASSERT_TRUE(pass);
    ASSERT_TRUE(pass->Covers(state.odometry.size()));
    EXPECT_FALSE(pass->Covers(state.odometry.size() + 1));
    const RunFolder run(options.out);
    EXPECT_EQ(ScratchFiles(run.root()), 3u);  // the segments' voxel sets and their columns, ScanContext's descriptors

    const auto from_chain = EvaluateRun(run, ReadRunState(run, false), options, config, log, pass.get());
    ASSERT_TRUE(from_chain);
    const std::string ground_truth = Contents(run.root() / "ground_truth_closures.txt");
    const std::string scan_context = Contents(run.root() / "pr_curve_scan_context.csv");
    const std::string metrics = Contents(run.metrics_json());
    pass.reset();
    EXPECT_EQ(ScratchFiles(run.root()), 0u);

    // The same evaluation from the data itself, without the ground truth's cache.
    fs::remove(run.root() / "ground_truth_closures.txt");
    const auto from_data = EvaluateRun(run, ReadRunState(run, false), options, config, log);
    ASSERT_TRUE(from_data);
    EXPECT_GT(from_chain->gt_scan_pairs, 100u);
    EXPECT_EQ(from_chain->gt_scan_pairs, from_data->gt_scan_pairs);
    EXPECT_EQ(from_chain->gt_closing_segment_pairs, from_data->gt_closing_segment_pairs);
    ASSERT_TRUE(from_chain->sweeps.count("scan_context"));
    EXPECT_GT(from_chain->sweeps.at("scan_context").curve.size(), 1u);
    EXPECT_EQ(Contents(run.root() / "ground_truth_closures.txt"), ground_truth);
    EXPECT_EQ(Contents(run.root() / "pr_curve_scan_context.csv"), scan_context);
    EXPECT_EQ(Contents(run.metrics_json()), metrics);
    EXPECT_EQ(ScratchFiles(run.root()), 0u);
}

TEST(EvaluationPass, IsMadeOnlyForACallerThatEvaluatesNext) {
    test::TempDir out;
    RunOptions options = test::QuietRunOptions(test::TinySimDataset(), out / "run");
    options.to = 99;
    options.poses = PoseSource::kDataset;
    PipelineConfig config;
    std::ostringstream log;
    std::unique_ptr<EvaluationPass> pass;
    // Without a caller that evaluates next, no pass is made.
    RunPipeline(options, config, log);
    EXPECT_EQ(ScratchFiles(options.out), 0u);
    options.force = true;
    RunPipeline(options, config, log, &pass);
    ASSERT_TRUE(pass);
    EXPECT_TRUE(pass->Covers(100));
}

}  // namespace
}  // namespace revisit
