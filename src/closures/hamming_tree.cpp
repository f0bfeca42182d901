#include "closures/hamming_tree.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <tuple>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace revisit {

HammingTree::HammingTree(const HammingTreeConfig& config) : config_(config) { nodes_.emplace_back(); }

std::int32_t HammingTree::Descend(const Descriptor& d, std::bitset<256>* used_bits) const {
    std::int32_t index = 0;
    while (!nodes_[index].is_leaf()) {
        const int bit = nodes_[index].bit;
        if (used_bits) used_bits->set(bit);
        index = nodes_[index].children[TestBit(d, bit) ? 1 : 0];
    }
    return index;
}

const std::vector<TreeEntry>& HammingTree::LeafOf(const Descriptor& descriptor) const {
    return nodes_[Descend(descriptor, nullptr)].entries;
}

namespace {

/// Appends to `out` the best match per map of one query descriptor in one leaf. Leaf entries are in
/// insertion order, hence grouped by map id (maps are added in order): one pass keeps the best per map;
/// ties go to the earlier keypoint. This loop is where matching spends its time: popcount clone.
REVISIT_POPCNT_CLONES void ScanLeaf(const std::vector<TreeEntry>& entries, const Descriptor& query, std::int32_t q,
                                    int max_distance, std::vector<TreeMatch>& out) {
    const std::size_t first = out.size();
    for (const auto& entry : entries) {
        const int distance = HammingDistance(query, entry.descriptor);
        if (distance >= max_distance) continue;
        if (out.size() > first && out.back().map_id == entry.map_id) {
            if (distance < out.back().distance) out.back() = {q, entry.map_id, entry.keypoint, distance};
        } else {
            out.push_back({q, entry.map_id, entry.keypoint, distance});
        }
    }
}

/// Appends with a bounded slack (1/8 + 4 entries) instead of doubling: memory per stored map matters,
/// and shrinking after every insert would copy the whole leaf each time.
void Append(std::vector<TreeEntry>& entries, const TreeEntry& entry) {
    if (entries.size() == entries.capacity()) entries.reserve(entries.size() + entries.size() / 8 + 4);
    entries.push_back(entry);
}

/// How many entries have each of the 256 bits on. Each descriptor byte indexes a table that spreads its
/// 8 bits over the 8 byte lanes of a word, so one addition counts 8 bits; lanes are flushed before they
/// can overflow: 32 additions per entry instead of one step per set bit.
std::array<int, 256> CountOnes(const std::vector<TreeEntry>& entries) {
    static const auto kSpread = [] {
        std::array<std::uint64_t, 256> table{};
        for (int byte = 0; byte < 256; ++byte) {
            for (int lane = 0; lane < 8; ++lane) table[byte] |= std::uint64_t((byte >> lane) & 1) << (8 * lane);
        }
        return table;
    }();
    std::array<int, 256> ones{};
    std::array<std::uint64_t, 32> lanes{};
    const auto flush = [&] {
        for (int k = 0; k < 32; ++k) {
            for (int lane = 0; lane < 8; ++lane) ones[8 * k + lane] += int((lanes[k] >> (8 * lane)) & 0xff);
        }
        lanes.fill(0);
    };
    int pending = 0;
    for (const auto& entry : entries) {
        for (int k = 0; k < 32; ++k) lanes[k] += kSpread[(entry.descriptor[k >> 3] >> (8 * (k & 7))) & 0xff];
        if (++pending == 255) flush(), pending = 0;
    }
    flush();
    return ones;
}

}  // namespace

std::vector<TreeMatch> HammingTree::Match(const std::vector<Descriptor>& query) const {
    // Fixed chunks of queries, so that each chunk's buffer is reserved once from the sizes of its leaves
    // (a bound on its matches) and the chunks concatenate in query order whatever the thread count.
    constexpr std::size_t kChunk = 32;
    std::vector<std::vector<TreeMatch>> chunks((query.size() + kChunk - 1) / kChunk);
    tbb::parallel_for(std::size_t(0), chunks.size(), [&](std::size_t c) {
        const std::size_t begin = c * kChunk, end = std::min(query.size(), begin + kChunk);
        std::array<std::int32_t, kChunk> leaves{};
        std::size_t bound = 0;
        for (std::size_t q = begin; q < end; ++q) {
            leaves[q - begin] = Descend(query[q], nullptr);
            bound += nodes_[leaves[q - begin]].entries.size();
        }
        chunks[c].reserve(bound);
        for (std::size_t q = begin; q < end; ++q) {
            ScanLeaf(nodes_[leaves[q - begin]].entries, query[q], std::int32_t(q), config_.max_distance, chunks[c]);
        }
    });
    std::size_t total = 0;
    for (const auto& chunk : chunks) total += chunk.size();
    std::vector<TreeMatch> matches;
    matches.reserve(total);
    for (const auto& chunk : chunks) matches.insert(matches.end(), chunk.begin(), chunk.end());
    return matches;
}

void HammingTree::Add(const std::vector<Descriptor>& descriptors, std::int32_t map_id) {
    std::vector<std::int32_t> touched;
    touched.reserve(descriptors.size());
    for (std::size_t i = 0; i < descriptors.size(); ++i) {
        const std::int32_t leaf = Descend(descriptors[i], nullptr);
        Append(nodes_[leaf].entries, {descriptors[i], map_id, std::int32_t(i)});
        touched.push_back(leaf);
    }
    size_ += descriptors.size();
    std::sort(touched.begin(), touched.end());  // deterministic split order
    touched.erase(std::unique(touched.begin(), touched.end()), touched.end());
    for (const std::int32_t leaf : touched) {
        const int size = int(nodes_[leaf].entries.size());
        // A leaf of near-identical descriptors (the same place seen again and again) has no balanced bit;
        // recounting its bits on every insert would cost O(leaf) per insert, so retry only after growth.
        if (size > config_.leaf_capacity && 2 * size >= 3 * nodes_[leaf].unsplittable_size) {
            std::bitset<256> used;  // the bits on the leaf's path, shared by all of its entries
            Descend(nodes_[leaf].entries.front().descriptor, &used);
            SplitLeaf(leaf, used);
        }
    }
}

std::vector<TreeMatch> HammingTree::MatchAndAdd(const std::vector<Descriptor>& descriptors, std::int32_t map_id) {
    auto matches = Match(descriptors);
    Add(descriptors, map_id);
    return matches;
}

void HammingTree::SplitLeaf(std::int32_t leaf, std::bitset<256> used_bits) {
    // Thesis Eq. (3.9): split on the unused bit that is on for closest to half of the descriptors.
    const std::array<int, 256> ones = CountOnes(nodes_[leaf].entries);
    const double n = double(nodes_[leaf].entries.size());
    int best_bit = -1;
    double best_gap = 2.0;
    for (int bit = 0; bit < 256; ++bit) {
        if (used_bits.test(bit)) continue;
        const double gap = std::abs(ones[bit] / n - 0.5);
        if (gap < best_gap) {
            best_gap = gap;
            best_bit = bit;
        }
    }
    if (best_bit < 0 || best_gap > config_.split_tolerance) {  // no balanced bit: the leaf stays large
        nodes_[leaf].unsplittable_size = std::int32_t(nodes_[leaf].entries.size());
        return;
    }

    const auto first_child = std::int32_t(nodes_.size());
    nodes_.emplace_back();
    nodes_.emplace_back();
    auto entries = std::move(nodes_[leaf].entries);
    nodes_[leaf].entries = {};
    nodes_[leaf].bit = std::int16_t(best_bit);
    nodes_[leaf].children[0] = first_child;
    nodes_[leaf].children[1] = first_child + 1;
    for (auto& entry : entries) {
        Append(nodes_[first_child + (TestBit(entry.descriptor, best_bit) ? 1 : 0)].entries, entry);
    }
    used_bits.set(best_bit);
    for (int side = 0; side < 2; ++side) {
        auto& child = nodes_[first_child + side].entries;
        child.shrink_to_fit();
        if (int(child.size()) > config_.leaf_capacity) SplitLeaf(first_child + side, used_bits);
    }
}

std::vector<TreeEntry> HammingTree::Entries() const {
    std::vector<TreeEntry> entries;
    entries.reserve(size_);
    for (const auto& node : nodes_) entries.insert(entries.end(), node.entries.begin(), node.entries.end());
    return entries;
}

std::size_t HammingTree::num_leaves() const {
    return std::size_t(std::count_if(nodes_.begin(), nodes_.end(), [](const Node& n) { return n.is_leaf(); }));
}

int HammingTree::depth() const {
    int deepest = 0;
    std::vector<std::pair<std::int32_t, int>> stack{{0, 0}};
    while (!stack.empty()) {
        const auto [index, d] = stack.back();
        stack.pop_back();
        deepest = std::max(deepest, d);
        if (!nodes_[index].is_leaf()) {
            stack.push_back({nodes_[index].children[0], d + 1});
            stack.push_back({nodes_[index].children[1], d + 1});
        }
    }
    return deepest;
}

std::size_t HammingTree::MemoryBytes() const {
    std::size_t bytes = nodes_.capacity() * sizeof(Node);
    for (const auto& node : nodes_) bytes += node.entries.capacity() * sizeof(TreeEntry);
    return bytes;
}

}  // namespace revisit
