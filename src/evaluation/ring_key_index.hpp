#pragma once
/// Exact k-nearest ring keys among the first scans of a sequence, for the ScanContext baseline.
/// SCManager searches a k-d tree (nanoflann) over the ring keys of every scan but the most recent;
/// comparing each query with every earlier scan instead costs O(n^2) over a sequence (an hour of
/// driving: 36,000 queries x 18,000 keys). Here the keys live in k-d trees over aligned blocks of
/// 2^j scans (j >= kMinLevel): the first `prefix` scans are the blocks of prefix's binary digits plus
/// fewer than 2^kMinLevel scans compared directly, so a query visits O(log n) trees, the largest
/// first, each searched once within the k-th distance the trees before it found (a search per tree
/// plus one for its ties cost 1.7 times as much on a 100,000-scan city drive).
#include <Eigen/Core>
#include <cstddef>
#include <memory>
#include <utility>
#include <vector>

namespace revisit {

class RingKeyIndex {
  public:
    /// The smallest block with a tree: 1024 scans (below that, direct comparison is as fast).
    static constexpr int kMinLevel = 10;

    /// `ring_keys`: one per scan, all of the same size. Every tree that a prefix of at most
    /// `max_prefix` scans uses is built here (in parallel, independently of the thread count).
    RingKeyIndex(const std::vector<Eigen::VectorXf>& ring_keys, std::size_t max_prefix);
    ~RingKeyIndex();
    RingKeyIndex(const RingKeyIndex&) = delete;
    RingKeyIndex& operator=(const RingKeyIndex&) = delete;

    /// The `k` scans in [0, prefix) whose ring keys are nearest to `key`, as (squared distance, scan),
    /// by ascending distance, ties by lower scan: the same as comparing with every scan of the prefix.
    std::vector<std::pair<float, std::size_t>> Nearest(const Eigen::VectorXf& key, std::size_t prefix, std::size_t k) const;

  private:
    struct Block;
    const std::vector<Eigen::VectorXf>& keys_;
    std::vector<float> packed_;                   ///< keys_ row after row, the trees' storage
    std::vector<std::unique_ptr<Block>> blocks_;  ///< by (level, start), see BlockSlot
    std::size_t dims_ = 0;
    std::size_t max_prefix_ = 0;
    std::size_t BlockSlot(int level, std::size_t start) const;
};

}  // namespace revisit
