/// "Why was a revisit missed?" on a crafted run: one overlapping map pair lost at each stage.
#include <gtest/gtest.h>

#include "pipeline/missed_revisits.hpp"

namespace revisit {
namespace {

ClosureRecord Record(int query, int ref, bool refined, bool verified, bool accepted, const std::string& reason) {
    ClosureRecord record;
    record.closure.query_id = query;
    record.closure.ref_id = ref;
    record.closure.num_inliers = 12;
    record.refined = refined;
    record.refinement.accepted = verified;
    record.accepted = accepted;
    record.reason = reason;
    return record;
}

TEST(MissedRevisits, NamesTheStageThatLostEachOverlappingPair) {
    RunState state;
    for (int m = 0; m < 10; ++m) {
        MapRecordSummary map;
        map.id = m;
        map.first_scan = std::size_t(10 * m);
        map.last_scan = map.first_scan + 9;
        state.maps.push_back(map);
    }
    state.map_of_scan = MapOfScan(state.maps, 100);
    // The reference says each later map k overlaps map k - 5 (scan 10k + 3 with scan 10(k - 5) + 4),
    // and map 9 also overlaps map 8 (too recent to compare), map 1 (no vote) and map 3 (not selected).
    std::vector<ScanPair> gt;
    for (std::size_t k = 5; k < 10; ++k) gt.push_back(MakeScanPair(10 * k + 3, 10 * (k - 5) + 4));
    gt.push_back(MakeScanPair(95, 85));
    gt.push_back(MakeScanPair(96, 15));
    gt.push_back(MakeScanPair(97, 35));
    state.comparisons = {
        {5, 0, 0, 0, ComparisonStage::kNotSelected, 4, 0},   // too few matches
        {9, 3, 0, 0, ComparisonStage::kNotSelected, 40, 0},  // enough votes, outside the top half
        {6, 1, 0, 0, ComparisonStage::kCompared, 30, 2},     // too few inliers, never returned as a closure
        {7, 2, 0, 0, ComparisonStage::kCompared, 40, 14},    // the refinement then rejected it
        {9, 8, 0, 0, ComparisonStage::kSkippedRecent, 0, 0},
        {9, 4, 0, 0, ComparisonStage::kCompared, 50, 20},
        {8, 3, 0, 0, ComparisonStage::kCompared, 45, 18},
    };
    state.closures = {Record(7, 2, true, false, false, "overlap 0.12 < 0.4"),
                      Record(8, 3, true, true, false, "inconsistent with other closures (PCM)"),
                      Record(9, 4, true, true, true, "")};
    ClosureTruth truth;
    truth.verdicts = {ClosureVerdict{true, {}, 0, 0, {}}};  // the one accepted closure, 9 -> 4, is true
    const MissedRevisits result = FindMissedRevisits(state, gt, truth, 10, 10);
    EXPECT_EQ(result.overlapping_pairs, 8u);
    EXPECT_EQ(result.found_pairs, 1u);
    ASSERT_EQ(result.missed.size(), 7u);
    auto stage_of = [&](int query, int ref) {
        for (const auto& m : result.missed)
            if (m.query_map == query && m.ref_map == ref) return std::string(MissStageName(m.stage));
        return std::string("not missed");
    };
    EXPECT_EQ(stage_of(5, 0), "too few matches");
    EXPECT_EQ(stage_of(6, 1), "too few inliers");
    EXPECT_EQ(stage_of(7, 2), "refinement rejected");
    EXPECT_EQ(stage_of(8, 3), "PCM rejected");
    EXPECT_EQ(stage_of(9, 4), "not missed");
    EXPECT_EQ(stage_of(9, 8), "never compared: skipped as recent");
    EXPECT_EQ(stage_of(9, 1), "never compared: not voted");
    EXPECT_EQ(stage_of(9, 3), "never compared: not selected (top half by votes)");
    EXPECT_EQ(result.per_stage.at(MissStage::kTooFewInliers), 1u);

    // The funnel: each pair counts at every stage up to the furthest it reached.
    EXPECT_EQ(result.detector.compared, 6u);        // every pair with a vote
    EXPECT_EQ(result.detector.enough_matches, 5u);  // but 5 -> 0 (4 votes)
    EXPECT_EQ(result.detector.ransac, 3u);          // 7 -> 2, 8 -> 3, 9 -> 4
    EXPECT_EQ(result.detector.refined, 2u);         // 8 -> 3, 9 -> 4
    EXPECT_EQ(result.detector.accepted, 1u);        // 9 -> 4
    EXPECT_EQ(result.proximity.compared, 0u);
    {
        // The proximity pass joins 9 -> 1, which the detector never compared: its own column.
        RunState with_proximity = state;
        ClosureRecord record = Record(9, 1, true, true, true, "");
        record.method = "proximity";
        with_proximity.closures.push_back(record);
        ClosureTruth both = truth;
        both.verdicts.push_back(ClosureVerdict{true, {}, 0, 0, {}});
        const MissedRevisits joined = FindMissedRevisits(with_proximity, gt, both, 10, 10);
        EXPECT_EQ(joined.found_pairs, 2u);
        EXPECT_EQ(joined.detector.accepted, 1u);
        EXPECT_EQ(joined.proximity.compared, 1u);
        EXPECT_EQ(joined.proximity.refined, 1u);
        EXPECT_EQ(joined.proximity.accepted, 1u);
    }

    // A false accepted closure does not find its pair.
    truth.verdicts[0].is_true = false;
    EXPECT_EQ(FindMissedRevisits(state, gt, truth, 10, 10).found_pairs, 0u);
}

}  // namespace
}  // namespace revisit
