#include "closures/descriptor_matching.hpp"

#include <cstdint>
#include <limits>

namespace revisit {
namespace {

struct Nearest {
    std::int32_t index = -1;
    std::int32_t distance = std::numeric_limits<std::int32_t>::max();
};

/// One pass over the distance matrix fills both directions' nearest neighbours.
REVISIT_POPCNT_CLONES void NearestBothWays(const std::vector<Descriptor>& query, const std::vector<Descriptor>& ref,
                                           std::vector<Nearest>& for_query, std::vector<Nearest>& for_ref) {
    for_query.assign(query.size(), {});
    for_ref.assign(ref.size(), {});
    for (std::size_t q = 0; q < query.size(); ++q) {
        Nearest& best = for_query[q];
        for (std::size_t r = 0; r < ref.size(); ++r) {
            const std::int32_t d = HammingDistance(query[q], ref[r]);
            if (d < best.distance) best = {std::int32_t(r), d};
            if (d < for_ref[r].distance) for_ref[r] = {std::int32_t(q), d};
        }
    }
}

}  // namespace

std::vector<FeatureMatch> MatchMutualBest(const std::vector<Descriptor>& query, const std::vector<Descriptor>& ref,
                                          int max_distance) {
    std::vector<Nearest> for_query, for_ref;
    NearestBothWays(query, ref, for_query, for_ref);
    std::vector<FeatureMatch> matches;
    for (std::size_t q = 0; q < query.size(); ++q) {
        const Nearest& best = for_query[q];
        if (best.index < 0 || best.distance >= max_distance) continue;
        if (for_ref[std::size_t(best.index)].index != std::int32_t(q)) continue;
        matches.push_back({std::int32_t(q), best.index, best.distance});
    }
    return matches;
}

}  // namespace revisit
