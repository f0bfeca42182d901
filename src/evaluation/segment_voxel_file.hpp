#pragma once
/// The ground truth's segment voxel sets (ground_truth_closures.hpp), made while the chain reads the
/// scans: each scan's voxels under its reference pose join the segment CutSegments would put it in,
/// and each finished segment's set goes to a scratch file (ScratchRecords, compressed: ~2.5 KB per scan
/// of a 16-beam drive at car speed). The evaluation then reads the sets back
/// instead of reading (or, for `sim:`, ray-casting) every scan a second time, and holds only the sets
/// still waiting for a revisit, as when it reads the scans. Each set's column counts (VoxelColumns) go
/// to a second scratch file: they settle most candidate pairs without the sets.
#include "evaluation/ground_truth_closures.hpp"
#include "evaluation/scratch_records.hpp"
#include "evaluation/voxel_set.hpp"

#include <Eigen/Geometry>
#include <cstddef>
#include <filesystem>
#include <vector>

namespace revisit {

class SegmentVoxelFile {
  public:
    /// Creates an exclusive temporary beside `file` (ScratchRecords); the destructor removes it.
    /// Segments of `segment_length` [m] of travel (GtClosureConfig).
    SegmentVoxelFile(const std::filesystem::path& file, double segment_length);
    SegmentVoxelFile(const SegmentVoxelFile&) = delete;
    SegmentVoxelFile& operator=(const SegmentVoxelFile&) = delete;

    /// The next scan, in order: its reference pose as the run folder stores it (AsStoredTumPose) and its
    /// voxels under that pose (ScanVoxels). Throws on a write error, naming the file.
    void Add(const Eigen::Isometry3d& T_world_sensor, const PackedVoxels& scan_voxels);
    /// Writes the last segment; Add may not follow.
    void Finish();

    std::size_t num_scans() const { return cutter_.num_scans(); }
    /// The segments, as CutSegments cuts the same poses (the last one written once Finish is called).
    const std::vector<GtSegment>& segments() const { return cutter_.segments(); }
    /// Segment `s`'s voxel set, exactly as accumulated. Safe to call from several threads.
    PackedVoxels Load(std::size_t s) const;
    /// ColumnsOf(Load(s)), from a record of its own (a few hundred bytes: read without the set).
    VoxelColumns LoadColumns(std::size_t s) const;

  private:
    void WriteOpenSegment();

    ScratchRecords records_;           ///< one per written segment
    ScratchRecords columns_;           ///< its VoxelColumns, one per written segment
    SegmentCutter cutter_;
    std::vector<std::size_t> voxels_;  ///< per written segment: its voxel count
    PackedVoxels open_;                ///< the last segment's set, not written yet
};

}  // namespace revisit
