#pragma once
/// Our own Hamming-distance binary search tree (HBST semantics; Schlegel & Grisetti, RA-L 2018;
/// METHOD.md section 4). Approximate nearest neighbour: a query descends by split bits to one leaf.
#include <bitset>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "closures/features.hpp"

namespace revisit {

struct HammingTreeConfig {
    int leaf_capacity = 100;        ///< a leaf with more descriptors is split (when a good bit exists)
    double split_tolerance = 0.1;   ///< split only if the best bit's on-fraction is within this of 0.5
    int max_distance = 50;          ///< [bits] a match needs a distance below this
};

struct TreeEntry {
    Descriptor descriptor;
    std::int32_t map_id = 0;
    std::int32_t keypoint = 0;  ///< index of the keypoint in its map
};

/// One query descriptor's best match within one map.
struct TreeMatch {
    std::int32_t query = 0;     ///< index of the query descriptor
    std::int32_t map_id = 0;
    std::int32_t keypoint = 0;  ///< keypoint index in the reference map
    std::int32_t distance = 0;  ///< [bits]
};

class HammingTree {
  public:
    explicit HammingTree(const HammingTreeConfig& config = {});

    /// For each query descriptor, the best match per map in its leaf (distance < max_distance), ordered
    /// by query index then map id. Deterministic; parallel over query descriptors.
    std::vector<TreeMatch> Match(const std::vector<Descriptor>& query) const;
    /// Inserts the descriptors of one map, then splits the touched leaves that overflow. Map ids must
    /// not decrease from one call to the next (Match relies on leaves being grouped by map id).
    void Add(const std::vector<Descriptor>& descriptors, std::int32_t map_id);
    /// HBST "match and add": query first, then insert.
    std::vector<TreeMatch> MatchAndAdd(const std::vector<Descriptor>& descriptors, std::int32_t map_id);

    /// The leaf a descriptor descends to (for tests and diagnostics).
    const std::vector<TreeEntry>& LeafOf(const Descriptor& descriptor) const;

    /// Every stored entry (leaf order); used to save the database.
    std::vector<TreeEntry> Entries() const;

    std::size_t size() const { return size_; }
    std::size_t num_leaves() const;
    int depth() const;                 ///< longest root-to-leaf path (number of split bits)
    std::size_t MemoryBytes() const;   ///< heap bytes held by the tree
    const HammingTreeConfig& config() const { return config_; }

  private:
    struct Node {
        std::int32_t children[2] = {-1, -1};
        std::int16_t bit = -1;  ///< split bit; -1 for a leaf
        std::int32_t unsplittable_size = 0;  ///< size at the last failed split; retried after growing by half
        std::vector<TreeEntry> entries;
        bool is_leaf() const { return bit < 0; }
    };
    std::int32_t Descend(const Descriptor& d, std::bitset<256>* used_bits) const;
    void SplitLeaf(std::int32_t leaf, std::bitset<256> used_bits);

    HammingTreeConfig config_;
    std::vector<Node> nodes_;
    std::size_t size_ = 0;
};

}  // namespace revisit
