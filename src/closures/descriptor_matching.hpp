#pragma once
/// Exhaustive matching of one map's descriptors against another's, for the geometric verification of a
/// candidate the tree voted for (docs/method.md, section 6, 2D RANSAC).
#include <vector>

#include "closures/closure.hpp"
#include "closures/features.hpp"

namespace revisit {

/// Every mutual best match between `query` and `ref` with a Hamming distance below `max_distance`
/// [bits], ordered by query index. A pair is kept only when each descriptor is the other's nearest
/// (ties: the lower index), so one keypoint never feeds two correspondences.
std::vector<FeatureMatch> MatchMutualBest(const std::vector<Descriptor>& query, const std::vector<Descriptor>& ref,
                                          int max_distance);

}  // namespace revisit
