#include "optimization/global_map.hpp"

#include <algorithm>
#include <cstdint>
#include <numeric>

#include "core/error.hpp"

namespace revisit {
namespace {

bool VoxelLess(const Voxel& a, const Voxel& b) {
    return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
}

/// The positions of the first point of each voxel in `voxels`, ascending by voxel.
std::vector<std::uint32_t> FirstOfEachVoxel(const std::vector<Voxel>& voxels) {
    std::vector<std::uint32_t> order(voxels.size());
    std::iota(order.begin(), order.end(), 0u);
    std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
        if (voxels[a] != voxels[b]) return VoxelLess(voxels[a], voxels[b]);
        return a < b;
    });
    order.erase(std::unique(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) { return voxels[a] == voxels[b]; }),
                order.end());
    return order;
}

}  // namespace

GlobalMapBuilder::GlobalMapBuilder(double voxel_size, std::size_t max_points) : voxel_size_(voxel_size), max_points_(max_points) {
    if (!(voxel_size > 0.0)) throw ConfigError("global map: voxel_size must be positive");
    ReserveForCap();
}

void GlobalMapBuilder::ReserveForCap() {
    // Reserved, not touched: no copies while they grow (the old and new arrays side by side), and no
    // pages until used. A map's points can pass the cap before they are thinned: a margin for those.
    // A cap set far beyond any map (to switch it off) reserves no more than this: its address space
    // could exceed the machine's, and the arrays grow as usual past it.
    constexpr std::size_t kMostReserved = std::size_t(1) << 23;  // [points] 100 MB of address space per array
    if (max_points_ == 0) return;
    const std::size_t capacity = std::min(max_points_ + max_points_ / 4, kMostReserved);
    points_.reserve(capacity);
    occupied_.reserve(capacity);
}

void GlobalMapBuilder::AddBatch(const std::vector<Eigen::Vector3f>& points_in_world, const std::vector<Voxel>& voxels) {
    // The first point of the map to reach a voxel no earlier map holds keeps it, in the map's order.
    batch_seen_.clear();
    std::vector<std::pair<Voxel, std::uint32_t>> fresh;  // (voxel, point), ascending by voxel
    for (std::uint32_t i = 0; i < voxels.size(); ++i)
        if (batch_seen_.insert(voxels[i]).second) fresh.emplace_back(voxels[i], i);
    std::sort(fresh.begin(), fresh.end(), [](const auto& a, const auto& b) { return VoxelLess(a.first, b.first); });
    auto from = occupied_.begin();  // the queries ascend: each search starts where the last one ended
    std::size_t kept = 0;
    for (const auto& entry : fresh) {
        from = std::lower_bound(from, occupied_.end(), entry.first, VoxelLess);
        if (from == occupied_.end() || *from != entry.first) fresh[kept++] = entry;
    }
    fresh.resize(kept);
    const std::size_t old_size = occupied_.size();
    for (const auto& entry : fresh) occupied_.push_back(entry.first);
    std::inplace_merge(occupied_.begin(), occupied_.begin() + static_cast<std::ptrdiff_t>(old_size), occupied_.end(), VoxelLess);
    std::sort(fresh.begin(), fresh.end(), [](const auto& a, const auto& b) { return a.second < b.second; });
    for (const auto& entry : fresh) points_.push_back(points_in_world[entry.second]);
    // Past the cap mid-map or at its end, the same points remain: a coarser voxel's first point is the
    // first point of one of the finer voxels in it, kept so far.
    while (max_points_ > 0 && points_.size() > max_points_) Coarsen();
}

void GlobalMapBuilder::Coarsen() {
    voxel_size_ *= 2.0;
    std::vector<Voxel>().swap(occupied_);  // release the old voxels before the new ones are listed
    std::vector<Voxel> voxels;
    voxels.reserve(points_.size());
    for (const auto& point : points_) voxels.push_back(VoxelOf(point.cast<double>(), voxel_size_));
    // In insertion order: the earliest of the points kept in a new voxel's eight old voxels is the first
    // point that reached it.
    std::vector<std::uint32_t> kept = FirstOfEachVoxel(voxels);
    ReserveForCap();
    for (const std::uint32_t i : kept) occupied_.push_back(voxels[i]);
    std::vector<Voxel>().swap(voxels);
    std::sort(kept.begin(), kept.end());
    std::size_t next = 0;
    for (const std::uint32_t i : kept) points_[next++] = points_[i];
    points_.resize(next);
}

}  // namespace revisit
