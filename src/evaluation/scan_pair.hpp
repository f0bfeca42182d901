#pragma once
/// A scan-level loop closure: an unordered pair of scan indices, stored sorted
/// (METHOD.md section 7: precision and recall are computed on sets of sorted scan pairs).
#include <cstddef>
#include <cstdint>
#include <functional>
#include <utility>

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

struct ScanPairHash {
    std::size_t operator()(const ScanPair& pair) const {
        const std::uint64_t key = (static_cast<std::uint64_t>(pair.first) << 32) ^ static_cast<std::uint64_t>(pair.second);
        return std::hash<std::uint64_t>{}(key * 0x9E3779B97F4A7C15ULL);
    }
};

/// A predicted scan-level closure with the detector's score (inliers, or a descriptor distance).
struct ScoredPair {
    ScanPair pair;
    double score = 0.0;
};

}  // namespace revisit
