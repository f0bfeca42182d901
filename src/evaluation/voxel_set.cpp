#include "evaluation/voxel_set.hpp"

#include <tsl/robin_map.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <utility>

#include "core/mix_bits.hpp"

namespace revisit {
namespace {

/// A block key's axes: 19 bits each, x highest (VoxelAxes::Block).
constexpr int kBlockAxisBits = 19;
constexpr std::uint64_t kBlockAxisMask = (std::uint64_t{1} << kBlockAxisBits) - 1;
std::uint64_t BlockX(std::uint64_t block) { return block >> (2 * kBlockAxisBits); }
std::uint64_t BlockY(std::uint64_t block) { return (block >> kBlockAxisBits) & kBlockAxisMask; }

/// A voxel's 21-bit axis values (around an offset: +-1048576 voxels, +-524 km at 0.5 m); the subsampling
/// hash takes its key (x << 42) | (y << 21) | z, so it keeps the same voxels whatever the packing.
struct VoxelAxes {
    std::uint64_t x, y, z;
    std::uint64_t Key() const { return (x << 42) | (y << 21) | z; }
    /// 19 bits per axis: the block of 4 x 4 x 4 voxels, in the same order as the voxel keys.
    std::uint64_t Block() const { return ((x >> 2) << (2 * kBlockAxisBits)) | ((y >> 2) << kBlockAxisBits) | (z >> 2); }
    std::uint64_t Bit() const { return std::uint64_t{1} << (((x & 3) << 4) | ((y & 3) << 2) | (z & 3)); }
};

/// A point's voxel: floor(value / voxel_size) per axis, without a division or a floor call per axis
/// where exactly the same: a power-of-two size divides as its reciprocal multiplies (both are the
/// correctly rounded x * 2^-k), and floor is truncation stepped down for negative fractions (exact
/// below 2^62; std::floor beyond and for NaN).
class VoxelGrid {
  public:
    explicit VoxelGrid(double voxel_size) : size_(voxel_size), inverse_(1.0 / voxel_size) {
        int exponent = 0;
        power_of_two_ = std::frexp(voxel_size, &exponent) == 0.5;
    }
    VoxelAxes AxesOf(const Eigen::Vector3d& point) const { return {Axis(point.x()), Axis(point.y()), Axis(point.z())}; }

  private:
    std::uint64_t Axis(double value) const {
        constexpr std::int64_t kOffset = 1 << 20;
        constexpr std::uint64_t kMask = (1ULL << 21) - 1;
        const double q = power_of_two_ ? value * inverse_ : value / size_;
        std::int64_t index;
        if (std::abs(q) < 0x1p62) {
            index = static_cast<std::int64_t>(q);
            index -= static_cast<double>(index) > q;
        } else {
            index = static_cast<std::int64_t>(std::floor(q));
        }
        return static_cast<std::uint64_t>(index + kOffset) & kMask;
    }
    double size_, inverse_;
    bool power_of_two_ = false;
};

/// Bits set in x (SWAR: no library call without -mpopcnt).
int PopCount(std::uint64_t x) {
    x = x - ((x >> 1) & 0x5555555555555555ULL);
    x = (x & 0x3333333333333333ULL) + ((x >> 2) & 0x3333333333333333ULL);
    x = (x + (x >> 4)) & 0x0F0F0F0F0F0F0F0FULL;
    return static_cast<int>((x * 0x0101010101010101ULL) >> 56);
}

struct BlockHash {
    std::size_t operator()(std::uint64_t key) const { return static_cast<std::size_t>(MixBits(key)); }
};

struct Block {
    std::uint64_t key;
    std::uint64_t mask;
};

/// Reads a packed set's blocks in order.
class PackedReader {
  public:
    explicit PackedReader(const PackedVoxels& set) : next_(set.bytes.data()), end_(set.bytes.data() + set.bytes.size()) {}
    bool Next(Block& block) {
        if (next_ == end_) return false;
        std::uint64_t gap = 0;
        for (int shift = 0;; shift += 7) {
            const std::uint8_t byte = *next_++;
            gap |= static_cast<std::uint64_t>(byte & 0x7F) << shift;
            if (!(byte & 0x80)) break;
        }
        key_ += gap;
        block.key = key_;
        std::memcpy(&block.mask, next_, sizeof(block.mask));
        next_ += sizeof(block.mask);
        return true;
    }

  private:
    const std::uint8_t* next_;
    const std::uint8_t* end_;
    std::uint64_t key_ = 0;
};

PackedVoxels Pack(const std::vector<Block>& sorted_blocks) {
    PackedVoxels set;
    set.bytes.reserve(sorted_blocks.size() * (3 + sizeof(std::uint64_t)));
    std::uint64_t last = 0;
    for (const Block& block : sorted_blocks) {
        for (std::uint64_t gap = block.key - last; ; gap >>= 7) {  // LEB128 varint
            if (gap < 0x80) {
                set.bytes.push_back(static_cast<std::uint8_t>(gap));
                break;
            }
            set.bytes.push_back(static_cast<std::uint8_t>(gap) | 0x80);
        }
        const std::size_t at = set.bytes.size();
        set.bytes.resize(at + sizeof(block.mask));
        std::memcpy(set.bytes.data() + at, &block.mask, sizeof(block.mask));
        set.size += static_cast<std::size_t>(PopCount(block.mask));
        last = block.key;
    }
    set.bytes.shrink_to_fit();
    return set;
}

std::vector<Block> Unpack(const PackedVoxels& set) {
    std::vector<Block> blocks;
    PackedReader reader(set);
    for (Block block{}; reader.Next(block);) blocks.push_back(block);
    return blocks;
}

}  // namespace

PackedVoxels ScanVoxels(const Eigen::Isometry3d& T_world_sensor, const std::vector<Eigen::Vector3f>& points_in_sensor,
                        double voxel_size, std::size_t subsample) {
    // Each block once, with the union of its voxels: a hash map and a sort of the distinct blocks
    // only (sorting every point's key was the evaluation's largest cost after reading the scans).
    tsl::robin_map<std::uint64_t, std::uint64_t, BlockHash> masks;
    masks.reserve(points_in_sensor.size() / 16 + 16);
    const VoxelGrid grid(voxel_size);
    std::uint64_t last_block = ~std::uint64_t{0}, last_mask = 0;  // neighbours along a ring mostly share a block
    for (const Eigen::Vector3f& p : points_in_sensor) {
        const VoxelAxes axes = grid.AxesOf(T_world_sensor * p.cast<double>());
        if (subsample > 1 && MixBits(axes.Key()) % subsample != 0) continue;
        const std::uint64_t block = axes.Block();
        if (block != last_block) {
            if (last_mask != 0) masks[last_block] |= last_mask;
            last_block = block;
            last_mask = 0;
        }
        last_mask |= axes.Bit();
    }
    if (last_mask != 0) masks[last_block] |= last_mask;
    std::vector<Block> scan_blocks;
    scan_blocks.reserve(masks.size());
    for (const auto& [block, mask] : masks) scan_blocks.push_back({block, mask});
    std::sort(scan_blocks.begin(), scan_blocks.end(), [](const Block& a, const Block& b) { return a.key < b.key; });
    return Pack(scan_blocks);
}

void MergeVoxels(PackedVoxels& voxels, const PackedVoxels& more) {
    if (more.size == 0) return;
    if (voxels.size == 0) {
        voxels = more;
        return;
    }
    // Both block lists are sorted: one merge, each block once with the union of its masks.
    std::vector<Block> merged = Unpack(voxels);
    const std::size_t held = merged.size();
    const std::vector<Block> added = Unpack(more);
    merged.insert(merged.end(), added.begin(), added.end());
    std::inplace_merge(merged.begin(), merged.begin() + static_cast<std::ptrdiff_t>(held), merged.end(),
                       [](const Block& a, const Block& b) { return a.key < b.key; });
    std::size_t out = 0;
    for (std::size_t k = 0; k < merged.size(); ++k) {
        if (out > 0 && merged[out - 1].key == merged[k].key) merged[out - 1].mask |= merged[k].mask;
        else merged[out++] = merged[k];
    }
    merged.resize(out);
    voxels = Pack(merged);
}

void AddVoxels(PackedVoxels& voxels, const Eigen::Isometry3d& T_world_sensor,
               const std::vector<Eigen::Vector3f>& points_in_sensor, double voxel_size, std::size_t subsample) {
    MergeVoxels(voxels, ScanVoxels(T_world_sensor, points_in_sensor, voxel_size, subsample));
}

double OverlapCoefficientAbove(const PackedVoxels& a, const PackedVoxels& b, double min_overlap) {
    if (a.size == 0 || b.size == 0) return 0.0;
    const std::size_t smaller = std::min(a.size, b.size);
    const auto ratio = [smaller](std::size_t common) { return static_cast<double>(common) / static_cast<double>(smaller); };
    // The most common voxels whose ratio is still at most min_overlap, by the same division as the
    // result (monotone): a bound at or below it proves the pair does not close, rounding included.
    std::size_t at_most = 0;
    const bool can_stop = min_overlap >= 0.0 && ratio(smaller) > min_overlap;
    if (can_stop) {
        at_most = static_cast<std::size_t>(min_overlap * static_cast<double>(smaller));
        while (at_most > 0 && ratio(at_most) > min_overlap) --at_most;
        while (ratio(at_most + 1) <= min_overlap) ++at_most;
    }
    std::size_t common = 0, left_a = a.size, left_b = b.size;
    PackedReader ra(a), rb(b);
    Block ba{}, bb{};
    bool more = ra.Next(ba) && rb.Next(bb);
    while (more) {
        if (ba.key < bb.key) {
            left_a -= static_cast<std::size_t>(PopCount(ba.mask));
            more = ra.Next(ba);
        } else if (bb.key < ba.key) {
            left_b -= static_cast<std::size_t>(PopCount(bb.mask));
            more = rb.Next(bb);
        } else {
            common += static_cast<std::size_t>(PopCount(ba.mask & bb.mask));
            left_a -= static_cast<std::size_t>(PopCount(ba.mask));
            left_b -= static_cast<std::size_t>(PopCount(bb.mask));
            more = ra.Next(ba) && rb.Next(bb);
        }
        if (can_stop && common + std::min(left_a, left_b) <= at_most) return ratio(common);
    }
    return ratio(common);
}

double OverlapCoefficient(const PackedVoxels& a, const PackedVoxels& b) { return OverlapCoefficientAbove(a, b, -1.0); }

VoxelColumns ColumnsOf(const PackedVoxels& set) {
    constexpr int kColumnShift = 3;  // 8 blocks of 4 voxels a side
    tsl::robin_map<std::uint64_t, std::uint64_t> counts;  // column (x << 32 | y) -> voxels
    PackedReader reader(set);
    for (Block block{}; reader.Next(block);) {
        const std::uint64_t x = BlockX(block.key) >> kColumnShift, y = BlockY(block.key) >> kColumnShift;
        counts[(x << 32) | y] += static_cast<std::uint64_t>(PopCount(block.mask));
    }
    VoxelColumns columns;
    columns.size = set.size;
    if (counts.empty()) return columns;
    std::vector<std::pair<std::uint64_t, std::uint64_t>> sorted(counts.begin(), counts.end());
    std::sort(sorted.begin(), sorted.end());
    columns.x0 = static_cast<std::uint32_t>(sorted.front().first >> 32);
    columns.y0 = std::numeric_limits<std::uint32_t>::max();
    for (const auto& [key, count] : sorted) columns.y0 = std::min(columns.y0, static_cast<std::uint32_t>(key));
    columns.cells.reserve(sorted.size());
    for (const auto& [key, count] : sorted) {
        const std::uint64_t dx = (key >> 32) - columns.x0, dy = (key & 0xFFFFFFFFu) - columns.y0;
        if (dx > 0xFF || dy > 0xFF || count > 0xFFFF) {
            columns.cells.clear();
            columns.bounded = false;
            return columns;
        }
        columns.cells.push_back(static_cast<std::uint32_t>(dx << 24 | dy << 16 | count));
    }
    return columns;
}

std::size_t CommonVoxelsAtMost(const VoxelColumns& a, const VoxelColumns& b) {
    if (!a.bounded || !b.bounded) return std::min(a.size, b.size);
    // The columns' absolute (x, y), in the order both lists are sorted in.
    const auto column = [](const VoxelColumns& c, std::uint32_t cell) {
        return (std::uint64_t{c.x0 + (cell >> 24)} << 32) | (c.y0 + ((cell >> 16) & 0xFF));
    };
    std::size_t common = 0;
    for (std::size_t i = 0, j = 0; i < a.cells.size() && j < b.cells.size();) {
        const std::uint64_t ka = column(a, a.cells[i]), kb = column(b, b.cells[j]);
        if (ka < kb) {
            ++i;
        } else if (kb < ka) {
            ++j;
        } else {
            common += std::min(a.cells[i] & 0xFFFF, b.cells[j] & 0xFFFF);
            ++i, ++j;
        }
    }
    return common;
}

}  // namespace revisit
