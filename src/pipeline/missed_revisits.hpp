#pragma once
/// "Why was a revisit missed?": for every pair of local maps that the reference says overlap (ground-truth
/// scan pairs between them) and that no true accepted closure joined, the stage of the chain that lost it.
#include <map>
#include <string>
#include <vector>

#include "evaluation/closure_truth.hpp"
#include "evaluation/scan_pair.hpp"
#include "runfolder/run_state.hpp"

namespace revisit {

/// Stages in chain order; a pair is reported at the furthest stage any of its records reached.
enum class MissStage {
    kSkippedRecent,        ///< never compared: a recent map of the same session
    kNotVoted,             ///< never compared: no descriptor of the query voted for the reference map
    kNotSelected,          ///< never compared: enough votes, but outside the paper's top half by votes
    kTooFewMatches,        ///< voted for, but below min_matches
    kTooFewInliers,        ///< RANSAC found fewer than gamma inliers
    kRefinementRejected,   ///< the 3D refinement rejected it (its reason is in `detail`)
    kConsistencyRejected,  ///< inconsistent with other closures (PCM)
    kGraphRejected,        ///< the pose graph switched it off
    kAcceptedFalse,        ///< accepted, but its pose disagrees with the reference
};
const char* MissStageName(MissStage stage);

struct MissedRevisit {
    int query_map = 0;  ///< the later map's id
    int ref_map = 0;    ///< the earlier map's id
    std::size_t gt_scan_pairs = 0;
    MissStage stage = MissStage::kNotVoted;
    std::string detail;  ///< votes, inliers or the rejection reason
};

/// Recall as a funnel: of the overlapping map pairs, how many reached each stage of one way of
/// finding closures. The detector passes every stage; the proximity pass has no votes or RANSAC
/// (it registers the pairs the corrected poses lay over each other), so only `compared`,
/// `refined` and `accepted` count for it.
struct RecallFunnel {
    std::size_t compared = 0;        ///< detector: the tree voted for the pair; proximity: registered
    std::size_t enough_matches = 0;  ///< detector: votes >= min_matches
    std::size_t ransac = 0;          ///< detector: RANSAC found >= gamma inliers
    std::size_t refined = 0;         ///< the 3D refinement accepted the pair
    std::size_t accepted = 0;        ///< a true closure of this way joins the pair after PCM and the graph
};

struct MissedRevisits {
    std::size_t overlapping_pairs = 0;  ///< map pairs with ground-truth scan pairs between them
    std::size_t found_pairs = 0;        ///< of those, joined by a true accepted closure
    RecallFunnel detector, proximity;
    std::map<MissStage, std::size_t> per_stage;
    std::vector<MissedRevisit> missed;  ///< sorted by query, then reference map
};

/// `truth` judges the accepted density closures of `state.closures`, in their order.
MissedRevisits FindMissedRevisits(const RunState& state, const std::vector<ScanPair>& gt_scan_pairs,
                                  const ClosureTruth& truth, int min_matches, int min_inliers);

}  // namespace revisit
