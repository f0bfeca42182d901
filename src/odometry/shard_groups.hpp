#pragma once
/// Voxels split among threads by hash shard (issue 19: the odometry map's batch update): each thread
/// owns the voxels of its shard, so a batch of points is added in parallel with the result of adding
/// them one by one.
#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/voxel.hpp"

namespace revisit {

/// Which of `num_shards` shards owns a voxel (a mixed hash: VoxelHash's low bits follow parities).
inline std::size_t ShardOf(const Voxel& voxel, std::size_t num_shards) {
    const std::uint64_t h = static_cast<std::uint64_t>(VoxelHash{}(voxel)) * 0x9E3779B97F4A7C15ull;
    return static_cast<std::size_t>(h >> 32) % num_shards;
}

/// Shards for `n` items: one per available thread, one for small inputs (not worth the tasks).
std::size_t NumShards(std::size_t n);

/// Indices 0..n-1 grouped by shard, each group in increasing order (a stable counting sort in
/// parallel chunks). A shard's task then walks only its own points: testing every point's shard
/// instead fails unpredictably (for half of them at two shards).
class ShardGroups {
  public:
    /// Groups by `shards[i]` < `num_shards`; keeps its buffers for the next call.
    void Build(const std::vector<std::uint32_t>& shards, std::size_t num_shards);
    const std::uint32_t* begin(std::size_t shard) const { return order_.data() + group_begin_[shard]; }
    const std::uint32_t* end(std::size_t shard) const { return order_.data() + group_begin_[shard + 1]; }

  private:
    std::vector<std::uint32_t> order_;       ///< point indices, shard by shard
    std::vector<std::size_t> positions_;     ///< per (chunk, shard): count, then next output position
    std::vector<std::size_t> group_begin_;   ///< per shard, and the end
};

}  // namespace revisit
