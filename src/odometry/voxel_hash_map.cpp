#include "odometry/voxel_hash_map.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <cmath>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "odometry/shard_groups.hpp"

namespace revisit {
namespace {

/// The 27 neighbour offsets ordered centre, faces, edges, corners: a near-optimal visiting
/// order for the pruned search (closer voxels first tighten the bound early).
std::array<Voxel, 27> MakeOffsets() {
    std::array<Voxel, 27> offsets;
    int n = 0;
    for (int ring = 0; ring <= 3; ++ring) {
        for (int x = -1; x <= 1; ++x) {
            for (int y = -1; y <= 1; ++y) {
                for (int z = -1; z <= 1; ++z) {
                    if (std::abs(x) + std::abs(y) + std::abs(z) == ring) offsets[n++] = Voxel(x, y, z);
                }
            }
        }
    }
    return offsets;
}
const std::array<Voxel, 27> kOffsets = MakeOffsets();
/// Per offset, per axis: 0 below, 1 same, 2 above (an index into a query's per-axis distances).
std::array<std::array<std::uint8_t, 3>, 27> MakeSides() {
    std::array<std::array<std::uint8_t, 3>, 27> sides;
    for (std::size_t k = 0; k < kOffsets.size(); ++k)
        for (int a = 0; a < 3; ++a) sides[k][a] = static_cast<std::uint8_t>(kOffsets[k][a] + 1);
    return sides;
}
const std::array<std::array<std::uint8_t, 3>, 27> kSides = MakeSides();
/// Index in kOffsets of the first voxel of each ring (centre, 6 faces, 12 edges, 8 corners).
constexpr std::size_t kFirstOfRing[4] = {0, 1, 7, 19};

// When a voxel's points span a plane (scale-free, so the same for any voxel size and sensor):
constexpr int kMinPlanePoints = 5;         ///< fewer points give no reliable normal
constexpr double kMaxThicknessRatio = 0.1;  ///< smallest / middle covariance eigenvalue: thin
/// Middle / largest eigenvalue: two-dimensional. A single ring line on a wall is thin in both other
/// directions (its range noise and nothing), which alone would pass as a plane with a normal along
/// the wall: this excludes it.
constexpr double kMinWidthRatio = 0.05;

/// The normal of the plane through `points` when they span one (see the constants above).
bool FitPlaneNormal(const Eigen::Vector3d* begin, const Eigen::Vector3d* end, Eigen::Vector3d& normal) {
    const auto n = end - begin;
    if (n < kMinPlanePoints) return false;
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    for (const Eigen::Vector3d* p = begin; p != end; ++p) mean += *p;
    mean /= static_cast<double>(n);
    Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
    for (const Eigen::Vector3d* p = begin; p != end; ++p) covariance.noalias() += (*p - mean) * (*p - mean).transpose();
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver;
    solver.computeDirect(covariance);
    const Eigen::Vector3d& lambda = solver.eigenvalues();  // ascending
    if (!(lambda[0] <= kMaxThicknessRatio * lambda[1]) || !(lambda[1] >= kMinWidthRatio * lambda[2])) return false;
    normal = solver.eigenvectors().col(0).normalized();
    return normal.allFinite();
}

/// The in-plane normal of the line through `points` (x, y only: a 2D laser's map, every point at one
/// height) when they lie along one: the 2D covariance's smallest eigenvalue below kMaxThicknessRatio of
/// the largest. The 3D fit would pick the vertical, in which such a map has no extent at all.
bool FitLineNormal(const Eigen::Vector3d* begin, const Eigen::Vector3d* end, Eigen::Vector3d& normal) {
    const auto n = end - begin;
    if (n < kMinPlanePoints) return false;
    Eigen::Vector2d mean = Eigen::Vector2d::Zero();
    for (const Eigen::Vector3d* p = begin; p != end; ++p) mean += p->head<2>();
    mean /= static_cast<double>(n);
    Eigen::Matrix2d covariance = Eigen::Matrix2d::Zero();
    for (const Eigen::Vector3d* p = begin; p != end; ++p) covariance.noalias() += (p->head<2>() - mean) * (p->head<2>() - mean).transpose();
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> solver;
    solver.computeDirect(covariance);
    const Eigen::Vector2d& lambda = solver.eigenvalues();  // ascending
    if (!(lambda[1] > 0.0) || !(lambda[0] <= kMaxThicknessRatio * lambda[1])) return false;
    normal = Eigen::Vector3d(solver.eigenvectors()(0, 0), solver.eigenvectors()(1, 0), 0.0).normalized();
    return normal.allFinite();
}

}  // namespace

VoxelHashMap::VoxelHashMap(double voxel_size, int max_points_per_voxel)
    : voxel_size_(voxel_size),
      inv_voxel_size_(1.0 / voxel_size),
      max_points_(std::max(1, max_points_per_voxel)),
      min_spacing2_(voxel_size * voxel_size / std::max(1, max_points_per_voxel)) {}

bool VoxelHashMap::TryAddToSlot(std::size_t slot, const Eigen::Vector3d& point) {
    seen_[slot] = stamp_;
    const int count = counts_[slot];
    if (count >= max_points_) return false;
    const Eigen::Vector3d* begin = points_.data() + slot * max_points_;
    const bool too_close = std::any_of(begin, begin + count, [&](const Eigen::Vector3d& p) {
        return (p - point).squaredNorm() < min_spacing2_;
    });
    if (too_close) return false;
    points_[slot * max_points_ + count] = point;
    ++counts_[slot];
    return true;
}

void VoxelHashMap::AddPoints(const std::vector<Eigen::Vector3d>& points) {
    // Same result as adding the points one by one in order, at any thread count (issue 19):
    // 1. in parallel, each thread owns the voxels of its hash shard and adds, in input order, the
    //    points that fall in voxels already in the map (the index is only read);
    // 2. serially, in input order, the points of new voxels: new slots are numbered as before.
    const std::size_t n = points.size();
    const std::size_t num_shards = NumShards(n);
    if (num_shards == 1) {  // small batches (2D scans, sparse sensors): the plain loop, no tasks
        for (const auto& point : points) AddPoint(point);
        UpdateNormals();
        return;
    }
    pending_.resize(n);
    point_voxels_.resize(n);
    point_shards_.resize(n);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 8192), [&](const auto& range) {
        for (std::size_t i = range.begin(); i != range.end(); ++i) {
            point_voxels_[i] = VoxelOfInverse(points[i], inv_voxel_size_);
            point_shards_[i] = static_cast<std::uint32_t>(ShardOf(point_voxels_[i], num_shards));
        }
    });
    shard_groups_.Build(point_shards_, num_shards);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, num_shards, 1), [&](const auto& range) {
        for (std::size_t s = range.begin(); s != range.end(); ++s) {
            for (const std::uint32_t* point = shard_groups_.begin(s); point != shard_groups_.end(s); ++point) {
                const std::size_t i = *point;
                const auto it = index_.find(point_voxels_[i]);
                pending_[i] = it == index_.end();
                if (!pending_[i]) TryAddToSlot(it->second, points[i]);
            }
        }
    });
    for (std::size_t i = 0; i < n; ++i)
        if (pending_[i]) AddPoint(points[i], point_voxels_[i]);
    UpdateNormals();
}

void VoxelHashMap::UpdateNormals() {
    if (!normals_enabled_) return;
    // New slots start with count 0: computed below. Each slot on its own: the same at any thread count.
    normals_.resize(voxels_.size(), Eigen::Vector3d::Zero());
    normal_ok_.resize(voxels_.size(), 0);
    normal_counts_.resize(voxels_.size(), 0);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, voxels_.size(), 4096), [&](const auto& range) {
        for (std::size_t slot = range.begin(); slot != range.end(); ++slot) {
            if (normal_counts_[slot] == counts_[slot]) continue;
            normal_counts_[slot] = counts_[slot];
            const Eigen::Vector3d* begin = points_.data() + slot * max_points_;
            const auto fit = normals_in_plane_ ? FitLineNormal : FitPlaneNormal;
            normal_ok_[slot] = fit(begin, begin + counts_[slot], normals_[slot]);
            if (normal_ok_[slot]) continue;
            // Too few points of its own (far from the sensor, sparse rings: often one ring's line), or
            // not a plane: the plane of its 27-voxel neighbourhood, if that is one.
            static thread_local std::vector<Eigen::Vector3d> gathered;
            gathered.clear();
            for (const Voxel& offset : kOffsets) {
                const auto it = index_.find(Voxel(voxels_[slot] + offset));
                if (it == index_.end()) continue;
                const Eigen::Vector3d* b = points_.data() + std::size_t(it->second) * max_points_;
                gathered.insert(gathered.end(), b, b + counts_[it->second]);
            }
            normal_ok_[slot] = fit(gathered.data(), gathered.data() + gathered.size(), normals_[slot]);
        }
    });
}

void VoxelHashMap::AddPoint(const Eigen::Vector3d& point) { AddPoint(point, VoxelOfInverse(point, inv_voxel_size_)); }

void VoxelHashMap::AddPoint(const Eigen::Vector3d& point, const Voxel& voxel) {
    const auto [it, inserted] = index_.try_emplace(voxel, static_cast<std::uint32_t>(voxels_.size()));
    if (!inserted) {
        TryAddToSlot(it->second, point);
        return;
    }
    voxels_.push_back(voxel);
    counts_.push_back(1);
    seen_.push_back(stamp_);
    points_.resize(points_.size() + max_points_);
    points_[static_cast<std::size_t>(it->second) * max_points_] = point;
}

void VoxelHashMap::RemoveFarFrom(const Eigen::Vector3d& origin, double max_distance, double oldest_kept) {
    const double max_distance2 = max_distance * max_distance;
    // The distance test in parallel; the swap-removal below is the serial one, so slots end up the same.
    far_.resize(voxels_.size());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, voxels_.size(), 8192), [&](const auto& range) {
        for (std::size_t slot = range.begin(); slot != range.end(); ++slot)
            far_[slot] = (points_[slot * max_points_] - origin).squaredNorm() > max_distance2 || seen_[slot] < oldest_kept;
    });
    // Normals follow their voxels (a stale cache, e.g. enabled after points were added, is rebuilt).
    const bool has_normals = normals_enabled_ && normals_.size() == voxels_.size();
    if (!has_normals) {
        normals_.clear();
        normal_ok_.clear();
        normal_counts_.clear();
    }
    std::size_t slot = 0;
    while (slot < voxels_.size()) {
        if (!far_[slot]) {
            ++slot;
            continue;
        }
        // Swap-remove: the last voxel moves into this slot, so storage stays dense.
        const std::size_t last = voxels_.size() - 1;
        index_.erase(voxels_[slot]);
        if (slot != last) {
            voxels_[slot] = voxels_[last];
            counts_[slot] = counts_[last];
            seen_[slot] = seen_[last];
            far_[slot] = far_[last];
            std::copy_n(points_.begin() + last * max_points_, counts_[last], points_.begin() + slot * max_points_);
            index_[voxels_[slot]] = static_cast<std::uint32_t>(slot);
            if (has_normals) {
                normals_[slot] = normals_[last];
                normal_ok_[slot] = normal_ok_[last];
                normal_counts_[slot] = normal_counts_[last];
            }
        }
        if (has_normals) {
            normals_.pop_back();
            normal_ok_.pop_back();
            normal_counts_.pop_back();
        }
        voxels_.pop_back();
        counts_.pop_back();
        seen_.pop_back();
        far_.pop_back();
        points_.resize(points_.size() - max_points_);
    }
}

void VoxelHashMap::Clear() {
    index_.clear();
    voxels_.clear();
    counts_.clear();
    seen_.clear();
    points_.clear();
    normals_.clear();
    normal_ok_.clear();
    normal_counts_.clear();
}

template <typename SlotOf>
const Eigen::Vector3d* VoxelHashMap::Search(const Eigen::Vector3d& query, double max_distance, const SlotOf& slot_of,
                                            double* other2) const {
    const Eigen::Vector3d scaled = query * inv_voxel_size_;
    const Voxel centre = FloorVoxel(scaled);
    const Eigen::Vector3d floor = centre.cast<double>();
    // Squared distance from the query to the lower and upper neighbour voxel along each axis.
    const Eigen::Vector3d below = (scaled - floor) * voxel_size_;
    const Eigen::Vector3d above = Eigen::Vector3d::Constant(voxel_size_) - below;
    const Eigen::Vector3d below2 = below.cwiseProduct(below);
    const Eigen::Vector3d above2 = above.cwiseProduct(above);
    // Per axis, the squared distance to the lower neighbour, the query's own layer (0) and the upper one.
    const double axis2[3][3] = {{below2[0], 0.0, above2[0]}, {below2[1], 0.0, above2[1]}, {below2[2], 0.0, above2[2]}};

    // Lower bounds of the edge and corner voxels' distances: the sums of the two and the three
    // smallest per-axis distances to the nearer face. Once the best point is closer, no voxel of
    // that ring can beat it, and the search ends there (the pruning below, without its 20 tests).
    // Summed in the loop's order, so each bound is exactly <= every box2 of its ring.
    const Eigen::Vector3d n2 = below2.cwiseMin(above2);
    const double ring_bound[4] = {0.0, 0.0, std::min({n2[0] + n2[1], n2[0] + n2[2], n2[1] + n2[2]}),
                                  (n2[0] + n2[1]) + n2[2]};

    double best2 = max_distance * max_distance;
    const Eigen::Vector3d* best = nullptr;
    // Second smallest distance of the visited points (points beyond max_distance count too), and
    // the distance bounds of the voxels not visited.
    double second2 = std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < kOffsets.size(); ++k) {
        if ((k == kFirstOfRing[2] || k == kFirstOfRing[3])) {
            const double bound = ring_bound[k == kFirstOfRing[2] ? 2 : 3];
            if (best2 <= bound) {
                second2 = std::min(second2, bound);
                break;
            }
        }
        // Looked up, not branched on; summed from 0 in axis order as the ring bounds are.
        const std::array<std::uint8_t, 3>& side = kSides[k];
        const double box2 = ((0.0 + axis2[0][side[0]]) + axis2[1][side[1]]) + axis2[2][side[2]];
        if (box2 >= best2) {
            second2 = std::min(second2, box2);
            continue;
        }
        const std::int64_t slot = slot_of(centre, k);
        if (slot < 0) continue;
        const Eigen::Vector3d* begin = points_.data() + std::size_t(slot) * max_points_;
        const Eigen::Vector3d* end = begin + counts_[std::size_t(slot)];
        if (other2 == nullptr) {
            for (const Eigen::Vector3d* p = begin; p != end; ++p) {
                const double d2 = (*p - query).squaredNorm();
                if (d2 < best2) {
                    best2 = d2;
                    best = p;
                }
            }
            continue;
        }
        for (const Eigen::Vector3d* p = begin; p != end; ++p) {
            const double d2 = (*p - query).squaredNorm();
            second2 = std::min(second2, std::max(best2, d2));  // a tie leaves second2 = best2: no reuse
            if (d2 < best2) {
                best2 = d2;
                best = p;
            }
        }
    }
    if (other2 != nullptr) *other2 = second2;
    return best;
}

const Eigen::Vector3d* VoxelHashMap::FindNearest(const Eigen::Vector3d& query, double max_distance) const {
    return Search(query, max_distance, [this](const Voxel& centre, std::size_t k) -> std::int64_t {
        const auto it = index_.find(Voxel(centre + kOffsets[k]));
        return it == index_.end() ? -1 : std::int64_t(it->second);
    });
}

const Eigen::Vector3d* VoxelHashMap::FindNearest(const Eigen::Vector3d& query, double max_distance,
                                                 Neighbourhood& cache) const {
    if (cache.nearest != nullptr && cache.max_distance == max_distance) {
        // The same unique nearest point as the last search while the query stays in its voxel and
        // moved less than half the gap to any other point (see Neighbourhood). The margin covers
        // the rounding of the distances (relative 1e-16, far below a micrometre per voxel).
        const double moved = (query - cache.searched_at).norm() + 1e-6 * voxel_size_;
        const double reach = cache.nearest_distance + moved;
        if (reach < cache.other_distance - moved && reach < max_distance &&
            VoxelOfInverse(query, inv_voxel_size_) == cache.centre) {
            return cache.nearest;
        }
    } else if (cache.max_distance == max_distance && max_distance > 0.0) {
        // Nothing within max_distance, and every point was at least other_distance away: after a move
        // by d, still nothing while other - d >= max_distance.
        const double moved = (query - cache.searched_at).norm() + 1e-6 * voxel_size_;
        if (cache.other_distance - moved >= max_distance && VoxelOfInverse(query, inv_voxel_size_) == cache.centre) {
            return nullptr;
        }
    }
    double other2 = 0.0;
    const Eigen::Vector3d* nearest = Search(query, max_distance, [this, &cache](const Voxel& centre, std::size_t k) -> std::int64_t {
        if (centre != cache.centre) {  // the query moved to another voxel: forget the old neighbours
            cache.centre = centre;
            cache.slots.fill(Neighbourhood::kUnknown);
        }
        // Looked up when first needed (pruned voxels never are), at most once per centre.
        if (cache.slots[k] == Neighbourhood::kUnknown) {
            const auto it = index_.find(Voxel(centre + kOffsets[k]));
            cache.slots[k] = it == index_.end() ? -1 : std::int32_t(it->second);
        }
        return cache.slots[k];
    }, &other2);
    cache.searched_at = query;
    cache.nearest = nearest;
    cache.nearest_distance = nearest ? (*nearest - query).norm() : 0.0;
    cache.other_distance = std::sqrt(other2);
    cache.max_distance = max_distance;
    return nearest;
}

std::size_t VoxelHashMap::NumPoints() const {
    std::size_t n = 0;
    for (const auto count : counts_) n += count;
    return n;
}

std::vector<Eigen::Vector3d> VoxelHashMap::Points() const {
    std::vector<Eigen::Vector3d> points;
    points.reserve(NumPoints());
    for (std::size_t slot = 0; slot < voxels_.size(); ++slot) {
        points.insert(points.end(), points_.begin() + slot * max_points_,
                      points_.begin() + slot * max_points_ + counts_[slot]);
    }
    return points;
}

void VoxelHashMap::PointsNear(const Eigen::Vector3d& origin, double radius, std::vector<Eigen::Vector3d>& out) const {
    const double radius2 = radius * radius;
    for (std::size_t slot = 0; slot < voxels_.size(); ++slot) {
        const Eigen::Vector3d& p = points_[slot * max_points_];
        if ((p - origin).squaredNorm() <= radius2) out.push_back(p);
    }
}

void VoxelHashMap::AllPointsNear(const Eigen::Vector3d& origin, double radius, std::vector<Eigen::Vector3d>& out) const {
    const double radius2 = radius * radius;
    for (std::size_t slot = 0; slot < voxels_.size(); ++slot) {
        if ((points_[slot * max_points_] - origin).squaredNorm() > radius2) continue;
        out.insert(out.end(), points_.begin() + static_cast<std::ptrdiff_t>(slot * max_points_),
                   points_.begin() + static_cast<std::ptrdiff_t>(slot * max_points_ + counts_[slot]));
    }
}

}  // namespace revisit
