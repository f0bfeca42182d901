#include <gtest/gtest.h>

#include <random>

#include "closures/hamming_tree.hpp"

namespace revisit {
namespace {

Descriptor RandomDescriptor(std::mt19937_64& rng) { return {rng(), rng(), rng(), rng()}; }

Descriptor FlipBits(Descriptor d, int count, std::mt19937_64& rng) {
    for (int i = 0; i < count; ++i) {
        const int bit = int(rng() % 256);
        d[bit >> 6] ^= (std::uint64_t(1) << (bit & 63));
    }
    return d;
}

/// Maps of random descriptors; queries are noisy copies of map 7's descriptors.
struct Fixture {
    std::vector<std::vector<Descriptor>> maps;
    std::vector<Descriptor> queries;
};

Fixture MakeFixture(int num_maps, int per_map, std::uint64_t seed) {
    std::mt19937_64 rng(seed);
    Fixture f;
    for (int m = 0; m < num_maps; ++m) {
        f.maps.emplace_back();
        for (int i = 0; i < per_map; ++i) f.maps.back().push_back(RandomDescriptor(rng));
    }
    for (const auto& d : f.maps[7]) f.queries.push_back(FlipBits(d, 12, rng));
    return f;
}

TEST(HammingTree, LeavesRespectCapacityAndDepthIsLogarithmic) {
    const auto f = MakeFixture(40, 500, 1);
    HammingTree tree;
    for (std::size_t m = 0; m < f.maps.size(); ++m) tree.Add(f.maps[m], std::int32_t(m));
    EXPECT_EQ(tree.size(), 20000u);
    for (const auto& d : f.maps[3]) EXPECT_LE(tree.LeafOf(d).size(), 100u);
    // Random descriptors split almost perfectly: 20000 / 100 needs ~8 levels; allow slack.
    EXPECT_GE(tree.depth(), 8);
    EXPECT_LE(tree.depth(), 16);
    EXPECT_GE(tree.num_leaves(), 200u);
}

TEST(HammingTree, MatchEqualsBruteForceWhenNearestIsInTheReachedLeaf) {
    const auto f = MakeFixture(30, 300, 2);
    HammingTree tree;
    for (std::size_t m = 0; m < f.maps.size(); ++m) tree.Add(f.maps[m], std::int32_t(m));
    const auto matches = tree.Match(f.queries);
    int checked = 0;
    for (std::size_t q = 0; q < f.queries.size(); ++q) {
        // Brute force over the whole database: best entry of map 7.
        int best = 256, best_index = -1;
        for (std::size_t i = 0; i < f.maps[7].size(); ++i) {
            const int d = HammingDistance(f.queries[q], f.maps[7][i]);
            if (d < best) best = d, best_index = int(i);
        }
        const auto& leaf = tree.LeafOf(f.queries[q]);
        const bool in_leaf = std::any_of(leaf.begin(), leaf.end(), [&](const TreeEntry& e) {
            return e.map_id == 7 && e.keypoint == best_index;
        });
        const auto it = std::find_if(matches.begin(), matches.end(), [&](const TreeMatch& m) {
            return m.query == std::int32_t(q) && m.map_id == 7;
        });
        if (in_leaf) {
            ++checked;
            ASSERT_NE(it, matches.end());
            EXPECT_EQ(it->keypoint, best_index);
            EXPECT_EQ(it->distance, best);
        }
    }
    EXPECT_GT(checked, 100);  // most noisy copies land in their original's leaf
}

TEST(HammingTree, ResultsAreDeterministicAndMatchThenAddSeesOnlyEarlierMaps) {
    const auto f = MakeFixture(12, 400, 3);
    HammingTree a, b;
    std::vector<std::vector<TreeMatch>> results_a, results_b;
    for (std::size_t m = 0; m < f.maps.size(); ++m) {
        results_a.push_back(a.MatchAndAdd(f.maps[m], std::int32_t(m)));
        results_b.push_back(b.MatchAndAdd(f.maps[m], std::int32_t(m)));
    }
    const auto qa = a.Match(f.queries), qb = b.Match(f.queries);
    ASSERT_EQ(qa.size(), qb.size());
    for (std::size_t i = 0; i < qa.size(); ++i) {
        EXPECT_EQ(qa[i].query, qb[i].query);
        EXPECT_EQ(qa[i].map_id, qb[i].map_id);
        EXPECT_EQ(qa[i].keypoint, qb[i].keypoint);
    }
    for (std::size_t m = 0; m < results_a.size(); ++m) {
        for (const auto& match : results_a[m]) EXPECT_LT(match.map_id, std::int32_t(m));
    }
    // Noisy copies of map 7 vote mostly for map 7, at most one match per map per query.
    int votes7 = 0;
    for (const auto& m : qa) votes7 += m.map_id == 7;
    EXPECT_GT(votes7, 200);
    for (std::size_t i = 1; i < qa.size(); ++i) {
        EXPECT_FALSE(qa[i].query == qa[i - 1].query && qa[i].map_id == qa[i - 1].map_id);
    }
}

TEST(HammingTree, IdenticalDescriptorsThatCannotSplitStayInOneLeaf) {
    std::mt19937_64 rng(4);
    const Descriptor d = RandomDescriptor(rng);
    HammingTree tree;
    tree.Add(std::vector<Descriptor>(250, d), 0);
    EXPECT_EQ(tree.num_leaves(), 1u);
    EXPECT_EQ(tree.LeafOf(d).size(), 250u);
    const auto matches = tree.Match({d});
    ASSERT_EQ(matches.size(), 1u);
    EXPECT_EQ(matches[0].distance, 0);
    EXPECT_EQ(matches[0].keypoint, 0);
}

}  // namespace
}  // namespace revisit
