#pragma once
/// A segment's voxel set for the ground-truth overlap (ground_truth_closures.hpp), packed in blocks.
#include <Eigen/Geometry>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace revisit {

/// Voxels grouped in blocks of 4 x 4 x 4: per block, in block order, the varint gap of its key from
/// the previous block's and the 64-bit mask of its voxels. Surfaces fill a block with several voxels,
/// so an overlap merges a block (an AND and a popcount) where it merged each voxel before (and the
/// set is smaller than one varint per voxel). The voxels, their count and every overlap are the same.
struct PackedVoxels {
    std::vector<std::uint8_t> bytes;
    std::size_t size = 0;  ///< voxels
};

/// The voxels (of `voxel_size`) of the points of one scan, moved by T_world_sensor; with `subsample`
/// > 1 only the voxels whose hash is 0 modulo it (the same voxels in every set).
PackedVoxels ScanVoxels(const Eigen::Isometry3d& T_world_sensor, const std::vector<Eigen::Vector3f>& points_in_sensor,
                        double voxel_size, std::size_t subsample);
/// `voxels` becomes the union of both sets (the same set whatever the order of the merges).
void MergeVoxels(PackedVoxels& voxels, const PackedVoxels& more);
/// MergeVoxels(voxels, ScanVoxels(...)).
void AddVoxels(PackedVoxels& voxels, const Eigen::Isometry3d& T_world_sensor,
               const std::vector<Eigen::Vector3f>& points_in_sensor, double voxel_size, std::size_t subsample);

/// Eq. (5.1): |A n B| / min(|A|, |B|); 0 when either set is empty.
double OverlapCoefficient(const PackedVoxels& a, const PackedVoxels& b);
/// The same when it exceeds `min_overlap`; otherwise some value at most `min_overlap`: the merge stops
/// once the voxels left in either set cannot lift the overlap above it (most candidate pairs of a
/// long drive do not close, and this is where the ground truth spends its time).
double OverlapCoefficientAbove(const PackedVoxels& a, const PackedVoxels& b, double min_overlap);

/// A set's voxels counted per vertical column of 8 x 8 blocks (16 m square at 0.5 m voxels, every
/// height): a few hundred bytes that bound the overlap of two sets without reading either. Two sets
/// share at most the smaller count of each column they both reach, and on a long drive most
/// candidate pairs (views of a place from tens of metres apart) are proven not to close by that alone.
struct VoxelColumns {
    std::uint32_t x0 = 0, y0 = 0;       ///< the lowest column along each axis
    std::vector<std::uint32_t> cells;  ///< (x - x0) << 24 | (y - y0) << 16 | count, sorted
    std::size_t size = 0;              ///< voxels of the set
    bool bounded = true;               ///< false: columns beyond 255 apart or with over 65535 voxels (no bound)
};

VoxelColumns ColumnsOf(const PackedVoxels& set);
/// At least |A n B| for the sets whose columns these are (their smaller size when either is unbounded).
std::size_t CommonVoxelsAtMost(const VoxelColumns& a, const VoxelColumns& b);

}  // namespace revisit
