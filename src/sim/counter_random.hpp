#pragma once
/// Counter-based random numbers: every draw is a hash of its key (seed, scan, ray, beam, place), so
/// results do not depend on the order of evaluation or the number of threads.
#include <cstdint>

namespace revisit {

/// SplitMix64 finalizer: a well-mixed 64-bit hash of x.
inline std::uint64_t SplitMix64(std::uint64_t x) {
    x += 0x9E3779B97F4A7C15ULL;
    x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ULL;
    x = (x ^ (x >> 27)) * 0x94D049BB133111EBULL;
    return x ^ (x >> 31);
}

/// Uniform in [0, 1) from a key.
inline double UnitFromKey(std::uint64_t key) { return static_cast<double>(SplitMix64(key) >> 11) * (1.0 / 9007199254740992.0); }

}  // namespace revisit
