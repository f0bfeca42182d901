/// Issue 16 on the real Livox handheld walk in ../shared: 266 keyframes, 58.5 m around a ~15 x 16 m
/// courtyard, back to 0.18 m from its start. Without a cap on the local maps' extent the handheld preset
/// cuts 3 maps and never compares the return with the start.
#include <gtest/gtest.h>

#include <sstream>

#include "pipeline/evaluate.hpp"
#include "pipeline/pipeline.hpp"
#include "test_data.hpp"

namespace revisit {
namespace {
namespace fs = std::filesystem;

struct WalkRun {
    RunState state;
    std::optional<RunEvaluation> evaluation;
};

WalkRun RunWalk(const fs::path& dataset, PoseSource poses) {
    // The handheld preset with the extent cap; recent maps are skipped by the revisit gap (20 m of
    // travel, what "revisit" means in the coverage), and the ground-truth closures need 20 m of travel
    // (0.4 x the preset's 50 m range) instead of 100 m, longer than the whole walk.
    const PipelineConfig config = LoadConfig(
        {(fs::path(REVISIT_SOURCE_DIR) / "configs/handheld.yaml").string()},
        {"local_map.max_extent=8", "detector.skip_recent_travel=20", "evaluation.travel_gap_ranges=0.4",
         "output.write_report=false", "output.scan_context=false", "output.elevation_ablation=false"});
    test::TempDir out;
    RunOptions options;
    options.dataset = dataset;
    options.out = out / "run";
    options.quiet = true;
    options.poses = poses;
    if (poses == PoseSource::kFile) {
        options.poses_file = dataset / "orig_odom_poses.txt";
        options.gt_file = dataset / "poses.txt";
    }
    std::ostringstream log;
    WalkRun run;
    run.state = RunPipeline(options, config, log);
    run.evaluation = EvaluateRun(RunFolder(options.out), run.state, options, config, log);
    return run;
}

TEST(RealWalk, LivoxHandheldWalkComparesTheReturnWithTheStartAndAcceptsNoFalseClosure) {
    const auto dataset = test::SharedData("livox_handheld_walk");
    REVISIT_REQUIRE_DATA(dataset);
    for (const PoseSource poses : {PoseSource::kDataset, PoseSource::kFile}) {
        SCOPED_TRACE(poses == PoseSource::kDataset ? "--poses dataset" : "--poses orig_odom_poses.txt --gt poses.txt");
        const WalkRun run = RunWalk(dataset, poses);
        ASSERT_TRUE(run.evaluation);
        const auto& state = run.state;
        const auto& e = *run.evaluation;
        ASSERT_GE(state.maps.size(), 5u);  // 5 with the 8 m cap
        EXPECT_EQ(e.truth.num_false, 0u);
        EXPECT_EQ(e.coverage.revisit_scans, 25u);  // ../shared/DATA.md: "about 25 frames come back within 3 m"

        // The return (last map) meets the start (map 0) with 20 RANSAC inliers, above gamma.
        const int last = state.maps.back().id;
        const ClosureRecord* back_home = nullptr;
        for (const auto& record : state.closures)
            if (record.method == "density" && record.closure.query_id == last && record.closure.ref_id == 0) back_home = &record;
        ASSERT_NE(back_home, nullptr);
        EXPECT_GE(back_home->closure.num_inliers, 15);
        // Measured: the 3D refinement rejects it (overlap / residual gates of the sparse 70-degree maps),
        // so no true closure covers the 25 revisiting scans; the miss table says so. With the refinement
        // gates relaxed (min_overlap 0.1, max_rms 1) it is accepted, 0.28 m / 0.1 deg from the reference,
        // and covers all 25.
        EXPECT_FALSE(back_home->accepted);
        EXPECT_DOUBLE_EQ(e.coverage.coverage, 0.0);
        bool named = false;
        for (const auto& missed : e.missed.missed)
            named |= missed.query_map == last && missed.ref_map == 0 && missed.stage == MissStage::kRefinementRejected;
        EXPECT_TRUE(named);
    }
}

}  // namespace
}  // namespace revisit
