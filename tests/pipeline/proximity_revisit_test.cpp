/// The proximity pass registers maps of one session only where the path came back between them
/// (proximity.revisit_detour; docs/method.md, "At the end of the run"). A simulated walk with a 16-ring
/// lidar along KITTI 00's first street: the sensor sees ~100 m, a map is ~15 m long, so maps a few
/// apart overlap although the walk never returns.
#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

#include "pipeline/pipeline.hpp"
#include "pipeline_run.hpp"
#include "sim/presets.hpp"
#include "sim/simulate.hpp"
#include "test_data.hpp"

namespace revisit {
namespace {
namespace fs = std::filesystem;

RunState RunWith(const fs::path& dataset, const fs::path& out, const std::vector<std::string>& overrides) {
    std::ostringstream log;
    return RunPipeline(test::QuietRunOptions(dataset, out), test::DefaultsFor(dataset, overrides), log);
}

/// Accepted proximity closures, each as its map pair.
std::vector<std::pair<int, int>> ProximityPairs(const RunState& state) {
    std::vector<std::pair<int, int>> pairs;
    for (const auto& record : state.closures)
        if (record.accepted && record.method == "proximity") pairs.emplace_back(record.closure.query_id, record.closure.ref_id);
    return pairs;
}

TEST(ProximityRevisit, MapsAFewApartAlongAPathThatNeverCameBackAreNotRegistered) {
    const auto route = test::SharedData("kitti_gt_poses/00.txt");
    REVISIT_REQUIRE_DATA(route);
    test::TempDir dir;
    SimConfig sim = AlongTrajectory(SimPreset("campus-vlp16"), route);
    sim.max_scans = 500;  // ~70 m of KITTI 00's first street, walked once
    RunSimulation(sim, dir / "walk", true);

    const RunState state = RunWith(dir / "walk", dir / "run", {});
    ASSERT_GE(state.maps.size(), 4u);
    EXPECT_TRUE(ProximityPairs(state).empty());
    // Nothing joins maps the odometry does not: the corrected poses are the odometry's.
    ASSERT_EQ(state.corrected.size(), state.odometry.size());
    for (std::size_t i = 0; i < state.odometry.size(); ++i)
        EXPECT_LT((state.corrected[i].translation() - state.odometry[i].translation()).norm(), 1e-6) << "scan " << i;

    // Every overlaid pair registered, as before: maps two and three apart join the graph (measured on
    // the 1,000-scan walk: 15 such closures, APE 0.0142 -> 0.0163 m).
    const RunState every_pair = RunWith(dir / "walk", dir / "run-every-pair", {"proximity.revisit_detour=0"});
    const auto pairs = ProximityPairs(every_pair);
    EXPECT_GE(pairs.size(), 2u);
    for (const auto& [query, ref] : pairs) EXPECT_GE(query - ref, 2) << query << "-" << ref;
}

}  // namespace
}  // namespace revisit
