#include <gtest/gtest.h>

#include "closures/descriptor_matching.hpp"

namespace revisit {
namespace {

/// A descriptor with the lowest `bits` bits set.
Descriptor WithBits(int bits, int offset = 0) {
    Descriptor d{0, 0, 0, 0};
    for (int b = offset; b < offset + bits; ++b) d[std::size_t(b >> 6)] |= std::uint64_t(1) << (b & 63);
    return d;
}

TEST(MatchMutualBest, KeepsOnlyPairsThatAreEachOthersNearest) {
    const std::vector<Descriptor> query = {WithBits(0), WithBits(10, 100), WithBits(3)};
    const std::vector<Descriptor> ref = {WithBits(1), WithBits(12, 100)};
    // query 0 and 2 both have ref 0 nearest (1 and 2 bits); ref 0's nearest is query 0: only (0, 0).
    // query 1 and ref 1 differ by 2 bits and are each other's nearest.
    const auto matches = MatchMutualBest(query, ref, 50);
    ASSERT_EQ(matches.size(), 2u);
    EXPECT_EQ(matches[0].query_keypoint, 0);
    EXPECT_EQ(matches[0].ref_keypoint, 0);
    EXPECT_EQ(matches[0].distance, 1);
    EXPECT_EQ(matches[1].query_keypoint, 1);
    EXPECT_EQ(matches[1].ref_keypoint, 1);
    EXPECT_EQ(matches[1].distance, 2);
}

TEST(MatchMutualBest, DropsPairsAtOrBeyondTheDistanceGate) {
    const std::vector<Descriptor> query = {WithBits(0)};
    const std::vector<Descriptor> ref = {WithBits(50)};
    EXPECT_TRUE(MatchMutualBest(query, ref, 50).empty());
    EXPECT_EQ(MatchMutualBest(query, ref, 51).size(), 1u);
    EXPECT_TRUE(MatchMutualBest(query, {}, 50).empty());
    EXPECT_TRUE(MatchMutualBest({}, ref, 50).empty());
}

}  // namespace
}  // namespace revisit
