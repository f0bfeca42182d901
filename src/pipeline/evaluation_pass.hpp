#pragma once
/// What the evaluation needs of every scan, made while the chain reads it: the ground truth's segment
/// voxel sets (SegmentVoxelFile) and ScanContext's descriptors (ScanContextFile), both in scratch files
/// of the run folder. `revisit run` then evaluates without a second pass over the data: on a long drive
/// that pass read (or, for `sim:`, ray-cast) every scan again and was most of the evaluation's time.
/// `revisit eval` on its own, with nothing of the chain's, reads the data as before; the results are
/// the same (the sets and descriptors are made from the same points under the same stored poses).
#include <Eigen/Geometry>
#include <cstddef>
#include <memory>
#include <optional>

#include "config/config.hpp"
#include "core/scan.hpp"
#include "evaluation/scan_context_file.hpp"
#include "evaluation/segment_voxel_file.hpp"
#include "runfolder/run_folder.hpp"

namespace revisit {

class EvaluationPass {
  public:
    /// One scan's share, computed on its own (any thread).
    struct ScanPart {
        std::optional<Eigen::Isometry3d> T_world_sensor;  ///< the reference pose as the run folder stores it
        PackedVoxels voxels;                              ///< under that pose
        std::optional<ScanContextDescriptor> scan_context;
    };

    /// Scratch files in `run`'s folder (removed with this object); ScanContext's only when
    /// config.output.scan_context.
    EvaluationPass(const RunFolder& run, const PipelineConfig& config);

    /// A scan's share from its points as read (sensor frame) and its reference pose, if it has one.
    ScanPart Prepare(const Scan& scan, const std::optional<Eigen::Isometry3d>& reference) const;
    /// The next scan's share, in the run's order. A scan without a reference pose ends the pass's use:
    /// the evaluation then covers part of the run and reads the data itself.
    void Add(ScanPart part);
    /// After the last scan.
    void Finish();

    /// Whether the pass holds every scan of a run of `run_scans` scans, each with its reference.
    bool Covers(std::size_t run_scans) const;
    const SegmentVoxelFile& segment_voxels() const { return *segment_voxels_; }
    /// ScanContext's descriptors (null when not made), handed to the evaluation.
    std::unique_ptr<ScanContextFile> TakeScanContext() { return std::move(scan_context_); }

  private:
    GtClosureConfig ground_truth_;
    ScanContextConfig scan_context_config_;
    std::unique_ptr<SegmentVoxelFile> segment_voxels_;
    std::unique_ptr<ScanContextFile> scan_context_;
    bool every_scan_referenced_ = true;  ///< else the pass stopped at the first scan without one
};

}  // namespace revisit
