#include "pipeline/evaluation_pass.hpp"

#include "io/trajectory_io.hpp"

namespace revisit {

EvaluationPass::EvaluationPass(const RunFolder& run, const PipelineConfig& config)
    : ground_truth_(config.ground_truth),
      scan_context_config_(config.scan_context),
      segment_voxels_(std::make_unique<SegmentVoxelFile>(run.root() / "segment_voxels.scratch", config.ground_truth.segment_length)) {
    if (config.output.scan_context) {
        scan_context_ = std::make_unique<ScanContextFile>(run.root() / "scan_context.scratch", config.scan_context.num_rings,
                                                          config.scan_context.num_sectors);
    }
}

EvaluationPass::ScanPart EvaluationPass::Prepare(const Scan& scan, const std::optional<Eigen::Isometry3d>& reference) const {
    ScanPart part;
    if (!reference) return part;
    // The evaluation reads the reference back from the run folder (9 decimals): the sets are made under
    // exactly those poses, so they are the ones a pass over the data would make.
    part.T_world_sensor = AsStoredTumPose(*reference);
    part.voxels = ScanVoxels(*part.T_world_sensor, scan.points, ground_truth_.voxel_size, ground_truth_.voxel_subsample);
    if (scan_context_) part.scan_context = MakeScanContext(scan.points, scan_context_config_);
    return part;
}

void EvaluationPass::Add(ScanPart part) {
    if (!every_scan_referenced_) return;
    if (!part.T_world_sensor) {
        every_scan_referenced_ = false;
        return;
    }
    segment_voxels_->Add(*part.T_world_sensor, part.voxels);
    if (scan_context_ && part.scan_context) scan_context_->Add(*part.scan_context);
}

void EvaluationPass::Finish() {
    if (every_scan_referenced_) segment_voxels_->Finish();
}

bool EvaluationPass::Covers(std::size_t run_scans) const {
    return every_scan_referenced_ && segment_voxels_->num_scans() == run_scans &&
           (!scan_context_ || scan_context_->size() == run_scans);
}

}  // namespace revisit
