#include "evaluation/ring_key_index.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

namespace revisit {
namespace {

/// What the index must return: every scan of the prefix compared, nearer first, ties by lower scan.
std::vector<std::pair<float, std::size_t>> DirectNearest(const std::vector<Eigen::VectorXf>& keys, const Eigen::VectorXf& key,
                                                         std::size_t prefix, std::size_t k) {
    std::vector<std::pair<float, std::size_t>> all;
    for (std::size_t s = 0; s < prefix; ++s) all.push_back({(key - keys[s]).squaredNorm(), s});
    std::sort(all.begin(), all.end());
    all.resize(std::min(k, all.size()));
    return all;
}

/// Ring keys like a drive's: a slowly changing profile (places), with stops where the same key
/// repeats exactly (ties) and revisits of earlier places.
std::vector<Eigen::VectorXf> DriveLikeKeys(std::size_t n, int rings, std::mt19937& rng) {
    std::normal_distribution<float> step(0.0f, 0.05f);
    std::vector<Eigen::VectorXf> keys;
    Eigen::VectorXf place = Eigen::VectorXf::Constant(rings, 1.0f);
    for (std::size_t s = 0; s < n; ++s) {
        if (s % 700 == 350 && s > 1000) {
            place = keys[s / 3];  // a revisit
        } else if (s % 97 >= 90 && !keys.empty()) {
            keys.push_back(keys.back());  // standing still: the very same key
            continue;
        } else {
            for (int r = 0; r < rings; ++r) place(r) = std::max(0.0f, place(r) + step(rng));
        }
        keys.push_back(place);
    }
    return keys;
}

TEST(RingKeyIndex, FindsTheSameNeighboursAsComparingEveryScan) {
    std::mt19937 rng(3);
    const std::size_t n = 5000;
    const auto keys = DriveLikeKeys(n, 20, rng);
    const RingKeyIndex index(keys, n);
    // Prefixes at, below and above block sizes, and k beyond a small prefix.
    for (std::size_t prefix : {std::size_t{1}, std::size_t{7}, std::size_t{1023}, std::size_t{1024}, std::size_t{1025},
                               std::size_t{2048}, std::size_t{3071}, std::size_t{3072}, std::size_t{4097}, n}) {
        for (std::size_t query : {std::size_t{0}, prefix / 2, n - 1, std::size_t{1400}, std::size_t{2101}}) {
            for (std::size_t k : {std::size_t{1}, std::size_t{10}, std::size_t{40}}) {
                const auto expected = DirectNearest(keys, keys[query], prefix, k);
                const auto found = index.Nearest(keys[query], prefix, k);
                ASSERT_EQ(found, expected) << "prefix " << prefix << ", query " << query << ", k " << k;
            }
        }
    }
    EXPECT_TRUE(index.Nearest(keys[0], 0, 10).empty());
    EXPECT_TRUE(index.Nearest(keys[0], n, 0).empty());
}

TEST(RingKeyIndex, KeepsTheLowerScansAmongEqualKeys) {
    // 3000 copies of one key: every distance ties, so the nearest are the first scans.
    const std::vector<Eigen::VectorXf> keys(3000, Eigen::VectorXf::Constant(20, 0.5f));
    const RingKeyIndex index(keys, keys.size());
    const auto found = index.Nearest(keys[0], 2500, 10);
    ASSERT_EQ(found.size(), 10u);
    for (std::size_t i = 0; i < found.size(); ++i) EXPECT_EQ(found[i].second, i);
}

TEST(RingKeyIndex, RefusesKeysOfDifferentSizes) {
    std::vector<Eigen::VectorXf> keys(3, Eigen::VectorXf::Zero(20));
    keys[1] = Eigen::VectorXf::Zero(19);
    EXPECT_ANY_THROW(RingKeyIndex(keys, keys.size()));
}

}  // namespace
}  // namespace revisit
