#pragma once
/// Counter-based random numbers: every draw is a hash of its key (seed, scan, ray, beam, place), so
/// results do not depend on the order of evaluation or the number of threads.
#include <cstdint>

#include "core/mix_bits.hpp"

namespace revisit {

/// One SplitMix64 step from state x: a well-mixed 64-bit hash of x.
inline std::uint64_t SplitMix64(std::uint64_t x) { return MixBits(x + 0x9E3779B97F4A7C15ULL); }

/// Uniform in [0, 1) from a key.
inline double UnitFromKey(std::uint64_t key) { return static_cast<double>(SplitMix64(key) >> 11) * (1.0 / 9007199254740992.0); }

}  // namespace revisit
