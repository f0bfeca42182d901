#pragma once
/// Voxel keys, their hash and first-point-per-voxel downsampling, shared by every stage.
#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace revisit {

using Voxel = Eigen::Vector3i;

/// Spatial hash of Teschner et al. 2003 (the one KISS-ICP uses).
struct VoxelHash {
    std::size_t operator()(const Voxel& voxel) const {
        const auto v = voxel.cast<std::uint32_t>();
        return static_cast<std::size_t>((v.x() * 73856093u) ^ (v.y() * 19349669u) ^ (v.z() * 83492791u));
    }
};

/// VoxelHash with its bits mixed into the low ones, which power-of-two tables (tsl::robin_*) use as
/// the bucket: VoxelHash's low bits follow the coordinates' parities. For sets only looked up or
/// walked in an order of their own.
struct MixedVoxelHash {
    std::size_t operator()(const Voxel& voxel) const {
        const std::uint64_t h = static_cast<std::uint64_t>(VoxelHash{}(voxel)) * 0x9E3779B97F4A7C15ull;
        return static_cast<std::size_t>(h >> 32);
    }
};

/// std::floor(x) as an int, for |x| < 2^31 (2^31 voxels of 5 cm are 100,000 km): the truncation, one
/// less below zero when x was not whole. The same value as the library floor and the cast, without
/// the floor's range test, which kept the per-point loops from pipelining (issue 19: the voxel index
/// was ~40% of a downsampling on KITTI scans, -18% for the whole downsampling).
template <typename Scalar>
inline int FloorToInt(Scalar x) {
    const int truncated = static_cast<int>(x);
    return truncated - static_cast<int>(x < static_cast<Scalar>(truncated));
}

/// The voxel of a point already scaled to voxel units (divided by the edge, or times its inverse).
template <typename Scalar>
inline Voxel FloorVoxel(const Eigen::Matrix<Scalar, 3, 1>& scaled) {
    return Voxel(FloorToInt(scaled.x()), FloorToInt(scaled.y()), FloorToInt(scaled.z()));
}

/// Integer voxel coordinates of a point for a voxel edge `voxel_size` [m].
inline Voxel VoxelOf(const Eigen::Vector3d& point, double voxel_size) {
    return FloorVoxel(Eigen::Vector3d(point / voxel_size));
}

/// Integer voxel coordinates of a point for a given inverse voxel size [1/m] (a multiplication
/// instead of VoxelOf's division: this runs for every point of a downsampling and every neighbour
/// query of the odometry's ICP).
inline Voxel VoxelOfInverse(const Eigen::Vector3d& point, double inv_voxel_size) {
    return FloorVoxel(Eigen::Vector3d(point * inv_voxel_size));
}

/// One point per voxel of edge `voxel_size` [m]: the first one met, so the result is deterministic
/// and keeps measured points (no centroids that smear edges). Throws ConfigError if voxel_size <= 0.
std::vector<Eigen::Vector3d> VoxelDownsample(const std::vector<Eigen::Vector3d>& points, double voxel_size);

}  // namespace revisit
