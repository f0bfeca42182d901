/// The online pose graph's updates (after accepted closures, each from the last update's estimate, and
/// further apart as the graph grows) are the live estimate only: the run's closures and corrected
/// trajectory come from the final optimization, which starts from the odometry (docs/method.md, "Pose
/// graph"). That is what lets the updates start warm and thin out on a long run without changing a run.
#include <gtest/gtest.h>

#include "pipeline_run.hpp"
#include "sim/presets.hpp"
#include "sim/simulate.hpp"
#include "test_data.hpp"

namespace revisit {
namespace {

TEST(OnlineUpdates, TheOutputsDoNotDependOnWhenTheUpdatesRan) {
    test::TempDir dir;
    const auto dataset = dir / "indoor.rawlog";
    RunSimulation(SimPreset("indoor-2d-180"), dataset, true);
    const RunState every = test::RunQuietly(dataset, test::DefaultsFor(dataset, {"graph.optimize_every_closures=1"}));
    const RunState never = test::RunQuietly(dataset, test::DefaultsFor(dataset, {"graph.optimize_every_closures=100000"}));

    ASSERT_EQ(every.closures.size(), never.closures.size());
    std::size_t accepted = 0;
    for (std::size_t k = 0; k < every.closures.size(); ++k) {
        EXPECT_EQ(every.closures[k].accepted, never.closures[k].accepted) << "closure " << k;
        EXPECT_EQ(every.closures[k].reason, never.closures[k].reason) << "closure " << k;
        EXPECT_EQ(every.closures[k].graph_weight, never.closures[k].graph_weight) << "closure " << k;
        accepted += every.closures[k].accepted;
    }
    // Measured: 19 accepted (18 from the proximity pass); the updates must have had closures to run after.
    ASSERT_GE(accepted, 5u) << "the case this test needs did not occur";
    ASSERT_EQ(every.corrected.size(), never.corrected.size());
    for (std::size_t i = 0; i < every.corrected.size(); ++i)
        EXPECT_EQ(every.corrected[i].matrix(), never.corrected[i].matrix()) << "scan " << i;
}

}  // namespace
}  // namespace revisit
