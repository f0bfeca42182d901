#include "pipeline/missed_revisits.hpp"

#include <algorithm>
#include <optional>
#include <utility>

namespace revisit {

const char* MissStageName(MissStage stage) {
    switch (stage) {
        case MissStage::kSkippedRecent: return "never compared: skipped as recent";
        case MissStage::kNotVoted: return "never compared: not voted";
        case MissStage::kNotSelected: return "never compared: not selected (top half by votes)";
        case MissStage::kTooFewMatches: return "too few matches";
        case MissStage::kTooFewInliers: return "too few inliers";
        case MissStage::kRefinementRejected: return "refinement rejected";
        case MissStage::kConsistencyRejected: return "PCM rejected";
        case MissStage::kGraphRejected: return "graph rejected";
        case MissStage::kAcceptedFalse: return "accepted, but false";
    }
    return "?";
}

namespace {

struct Outcome {
    MissStage stage = MissStage::kNotVoted;
    std::string detail;
    bool found = false;  ///< a true accepted closure joined the pair
    int detector_level = 0;   ///< furthest funnel stage of the detector: 1 compared .. 5 accepted
    int proximity_level = 0;  ///< the same for the proximity pass (1 registered, 4 refined, 5 accepted)
};

enum FunnelLevel { kCompared = 1, kEnoughMatches, kRansac, kRefined, kAccepted };

void Reach(int& level, int reached) { level = std::max(level, reached); }

void Count(RecallFunnel& funnel, int level) {
    funnel.compared += level >= kCompared;
    funnel.enough_matches += level >= kEnoughMatches;
    funnel.ransac += level >= kRansac;
    funnel.refined += level >= kRefined;
    funnel.accepted += level >= kAccepted;
}

using MapPair = std::pair<std::size_t, std::size_t>;  ///< (later, earlier) map index

void Raise(Outcome& outcome, MissStage stage, std::string detail) {
    if (outcome.stage == MissStage::kNotVoted || stage >= outcome.stage) {
        outcome.stage = stage;
        outcome.detail = std::move(detail);
    }
}

}  // namespace

MissedRevisits FindMissedRevisits(const RunState& state, const std::vector<ScanPair>& gt_scan_pairs,
                                  const ClosureTruth& truth, int min_matches, int min_inliers) {
    std::map<int, std::size_t> index_of_id;
    for (std::size_t m = 0; m < state.maps.size(); ++m) index_of_id[state.maps[m].id] = m;
    auto pair_of = [&](int a_id, int b_id) -> std::optional<MapPair> {
        const auto a = index_of_id.find(a_id), b = index_of_id.find(b_id);
        if (a == index_of_id.end() || b == index_of_id.end()) return std::nullopt;
        return std::make_pair(std::max(a->second, b->second), std::min(a->second, b->second));
    };

    std::map<MapPair, std::size_t> overlapping;
    for (const auto& pair : gt_scan_pairs) {
        if (pair.second >= state.map_of_scan.size()) continue;
        const int a = state.map_of_scan[pair.first], b = state.map_of_scan[pair.second];
        if (a < 0 || b < 0 || a == b) continue;
        ++overlapping[std::make_pair(std::size_t(std::max(a, b)), std::size_t(std::min(a, b)))];
    }

    std::map<MapPair, Outcome> outcomes;
    for (const auto& c : state.comparisons) {
        const auto key = pair_of(c.query_id, c.ref_id);
        if (!key || !overlapping.count(*key)) continue;
        Outcome& outcome = outcomes[*key];
        switch (c.stage) {
            case ComparisonStage::kSkippedRecent: Raise(outcome, MissStage::kSkippedRecent, ""); break;
            case ComparisonStage::kNotSelected:
                if (c.votes > 0) Reach(outcome.detector_level, c.votes >= min_matches ? kEnoughMatches : kCompared);
                if (c.votes < min_matches)
                    Raise(outcome, MissStage::kTooFewMatches, std::to_string(c.votes) + " votes < " + std::to_string(min_matches));
                else
                    Raise(outcome, MissStage::kNotSelected, std::to_string(c.votes) + " votes");
                break;
            case ComparisonStage::kCompared:
                Reach(outcome.detector_level, c.inliers >= min_inliers ? kRansac : kEnoughMatches);
                // At or above gamma the closure's own record says what happened next.
                if (c.inliers < min_inliers)
                    Raise(outcome, MissStage::kTooFewInliers, std::to_string(c.votes) + " votes, " + std::to_string(c.inliers) +
                                                                  " inliers < " + std::to_string(min_inliers));
                break;
        }
    }
    std::size_t accepted_index = 0;
    for (const auto& record : state.closures) {
        if (!CorrectsTrajectory(record)) continue;
        const bool is_true = record.accepted && accepted_index < truth.verdicts.size() && truth.verdicts[accepted_index].is_true;
        accepted_index += record.accepted ? 1 : 0;
        const auto& c = record.closure;
        const auto key = pair_of(c.query_id, c.ref_id);
        if (!key || !overlapping.count(*key)) continue;
        Outcome& outcome = outcomes[*key];
        const std::string counts = std::to_string(c.num_votes) + " votes, " + std::to_string(c.num_inliers) + " inliers";
        const bool proximity = record.method == "proximity";
        int& level = proximity ? outcome.proximity_level : outcome.detector_level;
        Reach(level, kCompared);
        if (!proximity && record.refined) Reach(level, kRansac);
        if (record.refined && record.refinement.accepted) Reach(level, kRefined);
        if (is_true) Reach(level, kAccepted);
        if (!record.refined) Raise(outcome, MissStage::kTooFewInliers, counts);
        else if (!record.refinement.accepted) Raise(outcome, MissStage::kRefinementRejected, record.reason);
        else if (!record.accepted && record.reason.find("PCM") != std::string::npos)
            Raise(outcome, MissStage::kConsistencyRejected, counts);
        else if (!record.accepted) Raise(outcome, MissStage::kGraphRejected, record.reason);
        else if (!is_true) Raise(outcome, MissStage::kAcceptedFalse, counts);
        else outcome.found = true;
    }

    MissedRevisits result;
    result.overlapping_pairs = overlapping.size();
    for (const auto& [key, gt_pairs] : overlapping) {
        const Outcome outcome = outcomes.count(key) ? outcomes[key] : Outcome{};
        Count(result.detector, outcome.detector_level);
        Count(result.proximity, outcome.proximity_level);
        if (outcome.found) {
            ++result.found_pairs;
            continue;
        }
        ++result.per_stage[outcome.stage];
        result.missed.push_back({state.maps[key.first].id, state.maps[key.second].id, gt_pairs, outcome.stage, outcome.detail});
    }
    return result;
}

}  // namespace revisit
