/// The table `revisit run` prints at the end: closure counts by stage and the APE change in words.
#include <gtest/gtest.h>

#include <sstream>

#include "pipeline/summary.hpp"

namespace revisit {
namespace {

std::string Summary(double ape_before, double ape_after) {
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
    PrintRunSummary(out, state, evaluation);
    return out.str();
}

TEST(RunSummary, CountsClosuresByStageAndNamesTheApeChange) {
    EXPECT_NE(Summary(1.0, 0.2).find("4 detected (>= 3 inliers), 3 refined in 3D, 2 verified, 1 accepted by the pose graph"),
              std::string::npos)
        << Summary(1.0, 0.2);
    EXPECT_NE(Summary(1.0, 0.2).find("1.0 m -> 0.2 m (80% lower)"), std::string::npos) << Summary(1.0, 0.2);
    EXPECT_NE(Summary(1.0, 1.5).find("(50% higher: the closures made it worse)"), std::string::npos) << Summary(1.0, 1.5);
    EXPECT_NE(Summary(1.0, 1.001).find("(0%: unchanged)"), std::string::npos) << Summary(1.0, 1.001);
    EXPECT_NE(Summary(1.0, 0.2).find("accepted closures: 1 true / 0 false"), std::string::npos) << Summary(1.0, 0.2);
    EXPECT_NE(Summary(1.0, 0.2).find("revisit coverage:  78% (31 of 40"), std::string::npos) << Summary(1.0, 0.2);
    EXPECT_NE(Summary(1.0, 0.2).find("overlapping map pairs: 3, found 1; too few inliers: 2"), std::string::npos)
        << Summary(1.0, 0.2);
}

}  // namespace
}  // namespace revisit
