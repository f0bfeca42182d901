#pragma once
/// A well-mixed 64-bit hash of a key: the SplitMix64 finalizer (Steele, Lea and Flood, "Fast
/// splittable pseudorandom number generators", 2014). Every bit of the result depends on every bit
/// of the key, so a hash taken modulo N does not follow a pattern of the keys (voxel coordinates,
/// counters).
#include <cstdint>

namespace revisit {

inline std::uint64_t MixBits(std::uint64_t x) {
    x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ULL;
    x = (x ^ (x >> 27)) * 0x94D049BB133111EBULL;
    return x ^ (x >> 31);
}

}  // namespace revisit
