#include "odometry/shard_groups.hpp"

#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>

namespace revisit {
namespace {
constexpr std::size_t kChunk = 8192;  ///< points per task of the element-wise passes
/// Fewer points take the serial path (the demo's 9,800 map points per scan are above it).
constexpr std::size_t kMinParallel = 4096;
}  // namespace

std::size_t NumShards(std::size_t n) {
    if (n < kMinParallel) return 1;
    // The arena's concurrency ignores a tbb::global_control limit (`--threads 1` still reports every
    // core), and the parallel path costs a single thread more than the serial one.
    const std::size_t allowed = tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism);
    return std::min(allowed, static_cast<std::size_t>(std::max(1, tbb::this_task_arena::max_concurrency())));
}

void ShardGroups::Build(const std::vector<std::uint32_t>& shards, std::size_t num_shards) {
    const std::size_t n = shards.size();
    const std::size_t chunks = (n + kChunk - 1) / kChunk;
    positions_.assign(chunks * num_shards, 0);
    tbb::parallel_for(std::size_t{0}, chunks, [&](std::size_t c) {
        std::size_t* counts = positions_.data() + c * num_shards;
        for (std::size_t i = c * kChunk, end = std::min(n, i + kChunk); i < end; ++i) ++counts[shards[i]];
    });
    // Shard-major prefix sum: shard s's points of chunk c follow those of chunks 0..c-1.
    group_begin_.resize(num_shards + 1);
    std::size_t position = 0;
    for (std::size_t s = 0; s < num_shards; ++s) {
        group_begin_[s] = position;
        for (std::size_t c = 0; c < chunks; ++c) {
            const std::size_t count = positions_[c * num_shards + s];
            positions_[c * num_shards + s] = position;
            position += count;
        }
    }
    group_begin_[num_shards] = position;
    order_.resize(n);
    tbb::parallel_for(std::size_t{0}, chunks, [&](std::size_t c) {
        std::size_t* next = positions_.data() + c * num_shards;
        for (std::size_t i = c * kChunk, end = std::min(n, i + kChunk); i < end; ++i)
            order_[next[shards[i]]++] = static_cast<std::uint32_t>(i);
    });
}

}  // namespace revisit
