#pragma once
/// A scan-level loop closure: an unordered pair of scan indices, stored sorted
/// (METHOD.md section 7: precision and recall are computed on sets of sorted scan pairs).
#include <algorithm>
#include <cstddef>
#include <utility>
#include <vector>

namespace revisit {

struct ScanPair {
    std::size_t first = 0;   ///< the smaller scan index
    std::size_t second = 0;  ///< the larger scan index

    friend bool operator==(const ScanPair& a, const ScanPair& b) { return a.first == b.first && a.second == b.second; }
    friend bool operator!=(const ScanPair& a, const ScanPair& b) { return !(a == b); }
    friend bool operator<(const ScanPair& a, const ScanPair& b) {
        return a.first != b.first ? a.first < b.first : a.second < b.second;
    }
};

/// The sorted pair of two scan indices, whatever their order.
inline ScanPair MakeScanPair(std::size_t a, std::size_t b) { return a < b ? ScanPair{a, b} : ScanPair{b, a}; }

/// `pairs` sorted, without repeats, each in MakeScanPair's order (a ground truth's scan pairs already
/// are: the sort is skipped).
inline std::vector<ScanPair> SortedUniquePairs(const std::vector<ScanPair>& pairs) {
    std::vector<ScanPair> sorted;
    sorted.reserve(pairs.size());
    for (const auto& pair : pairs) sorted.push_back(MakeScanPair(pair.first, pair.second));
    if (!std::is_sorted(sorted.begin(), sorted.end())) std::sort(sorted.begin(), sorted.end());
    sorted.erase(std::unique(sorted.begin(), sorted.end()), sorted.end());
    return sorted;
}

/// `pairs` itself when it already is what SortedUniquePairs makes (a ground truth's scan pairs are),
/// else SortedUniquePairs(pairs), kept in `storage`: a long drive's ground truth is not copied.
inline const std::vector<ScanPair>& AsSortedUniquePairs(const std::vector<ScanPair>& pairs, std::vector<ScanPair>& storage) {
    bool canonical = true;
    for (std::size_t k = 0; k < pairs.size() && canonical; ++k)
        canonical = pairs[k].first <= pairs[k].second && (k == 0 || pairs[k - 1] < pairs[k]);
    if (canonical) return pairs;
    storage = SortedUniquePairs(pairs);
    return storage;
}

/// A predicted scan-level closure with the detector's score (inliers, or a descriptor distance).
struct ScoredPair {
    ScanPair pair;
    double score = 0.0;
};

}  // namespace revisit
