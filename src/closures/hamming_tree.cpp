#include "closures/hamming_tree.hpp"

#include <algorithm>
#include <cmath>
#include <map>
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

/// Best match per map of one query descriptor in one leaf. Leaf entries are in insertion order, hence
/// grouped by map id (maps are added in order): one pass keeps the best per map; ties go to the earlier
/// keypoint. This loop is where matching spends its time, so it gets the popcount clone.
REVISIT_POPCNT_CLONES void ScanLeaf(const std::vector<TreeEntry>& entries, const Descriptor& query, std::int32_t q,
                                    int max_distance, std::vector<TreeMatch>& found) {
    for (const auto& entry : entries) {
        const int distance = HammingDistance(query, entry.descriptor);
        if (distance >= max_distance) continue;
        if (!found.empty() && found.back().map_id == entry.map_id) {
            if (distance < found.back().distance) found.back() = {q, entry.map_id, entry.keypoint, distance};
        } else {
            found.push_back({q, entry.map_id, entry.keypoint, distance});
        }
    }
}

/// Appends with a bounded slack (1/8 + 4 entries) instead of doubling: memory per stored map matters,
/// and shrinking after every insert would copy the whole leaf each time.
void Append(std::vector<TreeEntry>& entries, const TreeEntry& entry) {
    if (entries.size() == entries.capacity()) entries.reserve(entries.size() + entries.size() / 8 + 4);
    entries.push_back(entry);
}

}  // namespace

std::vector<TreeMatch> HammingTree::Match(const std::vector<Descriptor>& query) const {
    std::vector<std::vector<TreeMatch>> per_query(query.size());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, query.size(), 32), [&](const auto& range) {
        for (std::size_t q = range.begin(); q != range.end(); ++q) {
            ScanLeaf(nodes_[Descend(query[q], nullptr)].entries, query[q], std::int32_t(q), config_.max_distance,
                     per_query[q]);
        }
    });
    std::size_t total = 0;
    for (const auto& found : per_query) total += found.size();
    std::vector<TreeMatch> matches;
    matches.reserve(total);
    for (auto& found : per_query) matches.insert(matches.end(), found.begin(), found.end());
    return matches;
}

void HammingTree::Add(const std::vector<Descriptor>& descriptors, std::int32_t map_id) {
    std::map<std::int32_t, std::bitset<256>> touched;  // ordered: deterministic split order
    for (std::size_t i = 0; i < descriptors.size(); ++i) {
        std::bitset<256> used;
        const std::int32_t leaf = Descend(descriptors[i], &used);
        Append(nodes_[leaf].entries, {descriptors[i], map_id, std::int32_t(i)});
        touched.emplace(leaf, used);
    }
    size_ += descriptors.size();
    for (const auto& [leaf, used] : touched) {
        const int size = int(nodes_[leaf].entries.size());
        // A leaf of near-identical descriptors (the same place seen again and again) has no balanced bit;
        // recounting its bits on every insert would cost O(leaf) per insert, so retry only after growth.
        if (size > config_.leaf_capacity && 2 * size >= 3 * nodes_[leaf].unsplittable_size) SplitLeaf(leaf, used);
    }
}

std::vector<TreeMatch> HammingTree::MatchAndAdd(const std::vector<Descriptor>& descriptors, std::int32_t map_id) {
    auto matches = Match(descriptors);
    Add(descriptors, map_id);
    return matches;
}

void HammingTree::SplitLeaf(std::int32_t leaf, std::bitset<256> used_bits) {
    // Thesis Eq. (3.9): split on the unused bit that is on for closest to half of the descriptors.
    std::array<int, 256> ones{};
    for (const auto& entry : nodes_[leaf].entries) {
        for (int word = 0; word < 4; ++word) {
            for (std::uint64_t bits = entry.descriptor[word]; bits != 0; bits &= bits - 1) {
                ++ones[word * 64 + __builtin_ctzll(bits)];
            }
        }
    }
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
