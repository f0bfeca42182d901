#pragma once
/// Parallel, allocation-free per-frame filters of the odometry (issue 19: the serial steps made
/// parallel). Every result is identical to the serial definition at any thread count: points keep
/// their input order, and "the first point of a voxel" is the first in input order (each thread finds
/// the firsts of its contiguous chunk, then a chunk's first yields to any earlier chunk's).
#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <tsl/robin_set.h>
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

/// Keeps the buffers of the filters between frames: after the first frames nothing is allocated.
class ParallelFilter {
  public:
    /// CropRange (odometry/preprocess.hpp) into `out`: points with range in [min_range, max_range]
    /// [m] and finite, in double precision, input order; `kept`, when given, gets their input indices.
    void Crop(const std::vector<Eigen::Vector3f>& points, double min_range, double max_range,
              std::vector<Eigen::Vector3d>& out, std::vector<std::size_t>* kept);

    /// VoxelDownsample (core/voxel.hpp) into `out`: the first point of every voxel of edge
    /// `voxel_size` [m], input order. `out` must not alias `points`.
    void Downsample(const std::vector<Eigen::Vector3d>& points, double voxel_size, std::vector<Eigen::Vector3d>& out);

  private:
    /// Writes the flagged points, in order, with `write(i, position)`; returns how many.
    template <typename Write>
    std::size_t Compact(std::size_t n, const Write& write);

    std::vector<std::uint8_t> keep_;                           ///< per input point
    std::vector<std::size_t> chunk_offsets_;                   ///< output position of each chunk
    std::vector<tsl::robin_set<Voxel, VoxelHash>> seen_;       ///< per chunk of the downsampling
};

}  // namespace revisit
