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

/// Integer voxel coordinates of a point for a voxel edge `voxel_size` [m].
inline Voxel VoxelOf(const Eigen::Vector3d& point, double voxel_size) {
    return (point / voxel_size).array().floor().cast<int>();
}

/// One point per voxel of edge `voxel_size` [m]: the first one met, so the result is deterministic
/// and keeps measured points (no centroids that smear edges). Throws ConfigError if voxel_size <= 0.
std::vector<Eigen::Vector3d> VoxelDownsample(const std::vector<Eigen::Vector3d>& points, double voxel_size);

}  // namespace revisit
