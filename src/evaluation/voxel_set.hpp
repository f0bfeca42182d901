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

}  // namespace revisit
