#include "odometry/parallel_filter.hpp"

#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "core/error.hpp"
#include "odometry/preprocess.hpp"

namespace revisit {
namespace {
constexpr std::size_t kChunk = 8192;  ///< points per task of the element-wise passes
/// Fewer points take the serial paths. The demo's map points (9,800 per scan after the 0.5 v
/// downsampling) and their 1.5 v downsampling are above it: serial, they were ~10% of a scan's work.
constexpr std::size_t kMinParallel = 4096;
}  // namespace

std::size_t NumShards(std::size_t n) {
    if (n < kMinParallel) return 1;
    // The arena's concurrency ignores a tbb::global_control limit (`--threads 1` still reports every
    // core), and the parallel paths cost a single thread more than the serial ones (KITTI: 5.1 against
    // 3.7 ms of odometry per scan).
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

template <typename Write>
std::size_t ParallelFilter::Compact(std::size_t n, const Write& write) {
    // Count per fixed chunk, prefix sum, then write: positions depend on the flags only.
    const std::size_t chunks = (n + kChunk - 1) / kChunk;
    chunk_offsets_.assign(chunks + 1, 0);
    tbb::parallel_for(std::size_t{0}, chunks, [&](std::size_t c) {
        std::size_t count = 0;
        for (std::size_t i = c * kChunk, end = std::min(n, i + kChunk); i < end; ++i) count += keep_[i];
        chunk_offsets_[c + 1] = count;
    });
    for (std::size_t c = 0; c < chunks; ++c) chunk_offsets_[c + 1] += chunk_offsets_[c];
    tbb::parallel_for(std::size_t{0}, chunks, [&](std::size_t c) {
        std::size_t position = chunk_offsets_[c];
        for (std::size_t i = c * kChunk, end = std::min(n, i + kChunk); i < end; ++i)
            if (keep_[i]) write(i, position++);
    });
    return chunk_offsets_[chunks];
}

void ParallelFilter::Crop(const std::vector<Eigen::Vector3f>& points, double min_range, double max_range,
                          std::vector<Eigen::Vector3d>& out, std::vector<std::size_t>* kept) {
    const double min2 = min_range * min_range, max2 = max_range * max_range;
    const std::size_t n = points.size();
    if (NumShards(n) == 1) {  // small scans: the serial definition, no tasks
        out = CropRange(points, min_range, max_range, kept);
        return;
    }
    keep_.resize(n);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, kChunk), [&](const auto& range) {
        for (std::size_t i = range.begin(); i != range.end(); ++i) {
            const Eigen::Vector3d p = points[i].cast<double>();
            const double range2 = p.squaredNorm();
            keep_[i] = !(range2 < min2 || range2 > max2 || !p.allFinite());
        }
    });
    out.resize(n);  // capacity kept between frames; shrunk to the count below
    if (kept) kept->resize(n);
    const std::size_t count = Compact(n, [&](std::size_t i, std::size_t position) {
        out[position] = points[i].cast<double>();
        if (kept) (*kept)[position] = i;
    });
    out.resize(count);
    if (kept) kept->resize(count);
}

void ParallelFilter::Downsample(const std::vector<Eigen::Vector3d>& points, double voxel_size,
                                std::vector<Eigen::Vector3d>& out) {
    if (!(voxel_size > 0.0)) throw ConfigError("voxel_size must be positive");
    const double inv_voxel_size = 1.0 / voxel_size;
    const std::size_t n = points.size();
    const std::size_t num_shards = NumShards(n);
    if (num_shards == 1) {
        out = VoxelDownsample(points, voxel_size);
        return;
    }
    // Contiguous chunks, one per thread: each finds the first point of every voxel within itself; a
    // chunk's first is the global first unless an earlier chunk holds the voxel. No regrouping of the
    // points (which costs two more passes over them), and the same result at any chunk count.
    const std::size_t num_chunks = num_shards;
    const auto chunk_begin = [&](std::size_t c) { return n * c / num_chunks; };
    const auto voxel_of = [&](const Eigen::Vector3d& p) -> Voxel { return FloorVoxel(Eigen::Vector3d(p * inv_voxel_size)); };
    keep_.resize(n);
    if (seen_.size() < num_chunks) seen_.resize(num_chunks);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, num_chunks, 1), [&](const auto& range) {
        for (std::size_t c = range.begin(); c != range.end(); ++c) {
            auto& seen = seen_[c];
            seen.clear();  // keeps its buckets
            seen.reserve((chunk_begin(c + 1) - chunk_begin(c)) / 2);
            // Scan order puts neighbouring points next to each other: a point in the voxel of the
            // previous point is not the first of it, and needs no hash insertion.
            Voxel previous = Voxel::Zero();
            for (std::size_t i = chunk_begin(c); i < chunk_begin(c + 1); ++i) {
                const Voxel voxel = voxel_of(points[i]);
                keep_[i] = !(i > chunk_begin(c) && voxel == previous) && seen.insert(voxel).second;
                previous = voxel;
            }
        }
    });
    if (num_chunks > 1) {
        tbb::parallel_for(tbb::blocked_range<std::size_t>(chunk_begin(1), n, kChunk), [&](const auto& range) {
            std::size_t c = 1;
            for (std::size_t i = range.begin(); i != range.end(); ++i) {
                if (!keep_[i]) continue;
                while (i >= chunk_begin(c + 1)) ++c;
                const Voxel voxel = voxel_of(points[i]);
                for (std::size_t earlier = 0; earlier < c; ++earlier)
                    if (seen_[earlier].count(voxel) != 0) {
                        keep_[i] = 0;
                        break;
                    }
            }
        });
    }
    out.resize(n);
    out.resize(Compact(n, [&](std::size_t i, std::size_t position) { out[position] = points[i]; }));
}

}  // namespace revisit
