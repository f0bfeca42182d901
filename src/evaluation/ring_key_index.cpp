#include "evaluation/ring_key_index.hpp"

#include "core/error.hpp"

#include <nanoflann.hpp>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace revisit {

/// One aligned block of scans [start, start + size) and its k-d tree (nanoflann reads the keys
/// through this adaptor, without a copy).
struct RingKeyIndex::Block {
    const float* keys = nullptr;  ///< the block's first key in the packed storage
    std::size_t start = 0;
    std::size_t size = 0;
    std::size_t dims = 0;

    std::size_t kdtree_get_point_count() const { return size; }
    float kdtree_get_pt(std::size_t index, std::size_t dim) const { return keys[index * dims + dim]; }
    template <class Box>
    bool kdtree_get_bbox(Box&) const { return false; }

    using Tree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<float, Block, float>, Block, -1, std::size_t>;
    std::unique_ptr<Tree> tree;
};

namespace {

/// (squared distance, scan) in the order the search defines: nearer first, ties by lower scan.
using Neighbour = std::pair<float, std::size_t>;

/// The k nearest scans so far, over every block a query visits (nanoflann's result-set interface):
/// each tree is searched only within the k-th distance the earlier, larger blocks already found, once.
/// The trees measure distances in their own summation order; a point is re-measured as the direct
/// comparison measures it (`distance`), and the trees search within the k-th of those plus a margin
/// far above float rounding, so no point that ties or beats the k-th is left unvisited.
template <class Distance>
class SharedNearest {
  public:
    SharedNearest(std::size_t k, const Distance& distance) : k_(k), distance_(distance) { best_.reserve(k + 1); }

    void SetBlockStart(std::size_t start) { start_ = start; }
    std::size_t size() const { return best_.size(); }
    bool full() const { return best_.size() == k_; }
    float worstDist() const { return worst_; }
    bool addPoint(float, std::size_t index) {
        Consider(start_ + index);
        return true;
    }
    /// A scan compared directly (the few after the last block).
    void Consider(std::size_t scan) {
        const Neighbour candidate{distance_(scan), scan};
        if (full() && !(candidate < best_.back())) return;
        best_.insert(std::upper_bound(best_.begin(), best_.end(), candidate), candidate);
        if (best_.size() > k_) best_.pop_back();
        if (full()) worst_ = std::nextafter(best_.back().first * (1.0f + 1e-5f), std::numeric_limits<float>::max());
    }
    std::vector<Neighbour> Take() { return std::move(best_); }

  private:
    std::size_t k_;
    const Distance& distance_;
    std::size_t start_ = 0;
    std::vector<Neighbour> best_;  ///< ascending, at most k
    float worst_ = std::numeric_limits<float>::max();
};

}  // namespace

RingKeyIndex::RingKeyIndex(const std::vector<Eigen::VectorXf>& ring_keys, std::size_t max_prefix)
    : keys_(ring_keys), max_prefix_(std::min(max_prefix, ring_keys.size())) {
    dims_ = ring_keys.empty() ? 0 : static_cast<std::size_t>(ring_keys.front().size());
    for (const auto& key : ring_keys)
        if (static_cast<std::size_t>(key.size()) != dims_) throw ConfigError("scan context: ring keys of different sizes");
    std::vector<Block*> to_build;
    if (dims_ > 0 && max_prefix_ >= (std::size_t{1} << kMinLevel)) {
        packed_.resize(max_prefix_ * dims_);
        for (std::size_t s = 0; s < max_prefix_; ++s)
            std::copy(ring_keys[s].data(), ring_keys[s].data() + dims_, packed_.begin() + static_cast<std::ptrdiff_t>(s * dims_));
        // A prefix's block at level j starts after its higher digits: at a multiple of 2^(j+1).
        for (int level = kMinLevel; (std::size_t{1} << level) <= max_prefix_; ++level) {
            const std::size_t size = std::size_t{1} << level;
            for (std::size_t start = 0; start + size <= max_prefix_; start += 2 * size) {
                auto block = std::make_unique<Block>();
                block->keys = packed_.data() + start * dims_;
                block->start = start;
                block->size = size;
                block->dims = dims_;
                to_build.push_back(block.get());
                const std::size_t slot = BlockSlot(level, start);
                if (blocks_.size() <= slot) blocks_.resize(slot + 1);
                blocks_[slot] = std::move(block);
            }
        }
    }
    tbb::parallel_for(std::size_t{0}, to_build.size(), [&](std::size_t b) {
        Block& block = *to_build[b];
        block.tree = std::make_unique<Block::Tree>(dims_, block, nanoflann::KDTreeSingleIndexAdaptorParams(16));
    });
}

RingKeyIndex::~RingKeyIndex() = default;

/// Blocks are numbered level after level, and within a level by start / 2^(level+1).
std::size_t RingKeyIndex::BlockSlot(int level, std::size_t start) const {
    std::size_t slot = 0;
    for (int below = kMinLevel; below < level; ++below) slot += (max_prefix_ + (std::size_t{1} << below)) >> (below + 1);
    return slot + (start >> (level + 1));
}

std::vector<Neighbour> RingKeyIndex::Nearest(const Eigen::VectorXf& key, std::size_t prefix, std::size_t k) const {
    prefix = std::min(prefix, keys_.size());
    if (k == 0 || prefix == 0) return {};
    if (static_cast<std::size_t>(key.size()) != dims_) throw ConfigError("scan context: ring keys of different sizes");
    const auto distance = [&](std::size_t s) { return (key - keys_[s]).squaredNorm(); };
    SharedNearest<decltype(distance)> nearest(k, distance);
    std::size_t start = 0;
    if (prefix <= max_prefix_) {
        // Largest block first: its neighbours bound the search of the smaller ones.
        for (int level = 63; level >= kMinLevel; --level) {
            const std::size_t size = std::size_t{1} << level;
            if ((prefix & size) == 0) continue;
            const Block& block = *blocks_[BlockSlot(level, start)];
            nearest.SetBlockStart(block.start);
            block.tree->findNeighbors(nearest, key.data(), nanoflann::SearchParams(32, 0.0f, false));
            start += size;
        }
    }
    for (std::size_t s = start; s < prefix; ++s) nearest.Consider(s);
    return nearest.Take();
}

}  // namespace revisit
