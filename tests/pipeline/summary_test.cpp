/// The table `revisit run` prints at the end: closure counts by stage and the APE change in words.
#include <gtest/gtest.h>

#include <sstream>

#include "pipeline/summary.hpp"

namespace revisit {
namespace {

std::string Summary(double ape_before, double ape_after, const PostRunSeconds& after_chain = {}) {
    RunState state;
    ClosureRecord below_gamma, failed_refinement, graph_rejected, accepted;
    failed_refinement.refined = graph_rejected.refined = accepted.refined = true;
    graph_rejected.refinement.accepted = accepted.refinement.accepted = true;
    accepted.accepted = true;
    state.closures = {below_gamma, failed_refinement, graph_rejected, accepted};
    RunEvaluation evaluation;
    evaluation.odometry.ape.errors.translation_stats.rmse = ape_before;
    evaluation.corrected.ape.errors.translation_stats.rmse = ape_after;
    evaluation.truth.num_true = 1;
    evaluation.coverage = {40, 31, 31.0 / 40.0};
    evaluation.missed.overlapping_pairs = 3;
    evaluation.missed.found_pairs = 1;
    evaluation.missed.per_stage = {{MissStage::kTooFewInliers, 2}};
    std::ostringstream out;
    state.wall_seconds = 8.0;
    PrintRunSummary(out, state, evaluation, after_chain);
    return out.str();
}

TEST(RunSummary, CountsClosuresByStageAndNamesTheApeChange) {
    EXPECT_NE(Summary(1.0, 0.2).find("4 detected (>= 3 inliers), 3 refined in 3D, 2 verified, 1 accepted by the pose graph"),
              std::string::npos)
        << Summary(1.0, 0.2);
    EXPECT_NE(Summary(1.0, 0.2).find("1.00 m -> 0.20 m (80% lower)"), std::string::npos) << Summary(1.0, 0.2);
    EXPECT_NE(Summary(1.0, 1.5).find("(50% higher: the closures made it worse)"), std::string::npos) << Summary(1.0, 1.5);
    EXPECT_NE(Summary(1.0, 1.001).find("1.00 m -> 1.00 m (unchanged)"), std::string::npos) << Summary(1.0, 1.001);
    EXPECT_NE(Summary(1.0, 0.2).find("accepted closures: 1 true / 0 false"), std::string::npos) << Summary(1.0, 0.2);
    EXPECT_NE(Summary(1.0, 0.2).find("revisit coverage:  78% (31 of 40"), std::string::npos) << Summary(1.0, 0.2);
    EXPECT_NE(Summary(1.0, 0.2).find("overlapping map pairs: 3, found 1; too few inliers: 2"), std::string::npos)
        << Summary(1.0, 0.2);
}

TEST(RunSummary, ApeChangesBetweenValuesNearZeroAreUnchangedNotThousandsOfPercent) {
    // --poses dataset: the odometry is the reference, both errors are numerical noise.
    EXPECT_NE(Summary(1e-5, 1.4e-3).find("0.00 m -> 0.00 m (unchanged)"), std::string::npos) << Summary(1e-5, 1.4e-3);
    EXPECT_EQ(DescribeApeChange(1e-5, 1.4e-3).find('%'), std::string::npos);
    // Within the 1 cm the summary prints, also for larger values.
    EXPECT_NE(DescribeApeChange(2.0, 2.008).find("(unchanged)"), std::string::npos);
    // From near zero to a real error: metres, not a percentage.
    EXPECT_EQ(DescribeApeChange(0.001, 0.5), "0.00 m -> 0.50 m (+0.50 m: the closures made it worse)");
    EXPECT_EQ(DescribeApeChange(0.004, 0.0), "0.00 m -> 0.00 m (unchanged)");
    EXPECT_EQ(DescribeApeChange(0.5, 0.05), "0.50 m -> 0.05 m (90% lower)");
    // The reference is the input poses: the change is how far the closures moved them, not "worse".
    EXPECT_EQ(DescribeApeChange(0.0, 0.08, true),
              "0.00 m -> 0.08 m (reference = input poses: the closures moved the trajectory this far from them)");
}

TEST(RunSummary, WallTimeIncludesEvaluationAndReportEachShown) {
    const std::string summary = Summary(1.0, 0.2, {2.5, 4.0});
    EXPECT_NE(summary.find("wall time         14.5 s: chain 8.0 s"), std::string::npos) << summary;
    EXPECT_NE(summary.find("evaluation 2.5 s, report 4.0 s"), std::string::npos) << summary;
    EXPECT_EQ(Summary(1.0, 0.2).find("report"), std::string::npos);  // not run: not shown
}

TEST(RunSummary, CpuTimePerScanCountsTheEvaluationsShareMadeInTheChain) {
    RunState state;
    state.odometry.assign(1000, Eigen::Isometry3d::Identity());
    state.wall_seconds = 12.0;
    state.timings["evaluation.pass"] = StageTimer{500.0, 1000};  // 0.5 s of CPU in the chain
    PostRunSeconds after_chain;
    after_chain.evaluation = 2.0;
    after_chain.chain_cpu = 20.0;
    after_chain.evaluation_cpu = 1.5;
    after_chain.report_cpu = 3.0;
    std::ostringstream out;
    PrintRunSummary(out, state, std::nullopt, after_chain);
    EXPECT_NE(out.str().find("CPU time          chain 20.0 s (20.00 ms per scan), evaluation 1.5 s after it + 0.5 s in it "
                             "(2.00 ms per scan), report 3.0 s\n"),
              std::string::npos)
        << out.str();
    std::ostringstream without;
    PrintRunSummary(without, state, std::nullopt, {});
    EXPECT_EQ(without.str().find("CPU time"), std::string::npos);  // not measured: not shown
}

}  // namespace
}  // namespace revisit
