#include "evaluation/segment_voxel_file.hpp"

#include "core/error.hpp"

namespace revisit {
namespace {

double PositiveLength(double segment_length) {
    if (!(segment_length > 0.0)) throw ConfigError("ground truth: segment_length must be positive");
    return segment_length;
}

}  // namespace

SegmentVoxelFile::SegmentVoxelFile(const std::filesystem::path& file, double segment_length)
    : records_(file, "segment voxel set"), segment_length_(PositiveLength(segment_length)) {}

void SegmentVoxelFile::Add(const Eigen::Isometry3d& T_world_sensor, const PackedVoxels& scan_voxels) {
    // CutSegments' rule on CumulativeDistance's sums, one scan at a time.
    const Eigen::Vector3d position = T_world_sensor.translation();
    if (last_position_) travel_ += (position - *last_position_).norm();
    last_position_ = position;
    const std::size_t scan = num_scans_++;
    if (segments_.empty() || travel_ - segments_.back().start_travel >= segment_length_) {
        if (!segments_.empty()) WriteOpenSegment();
        segments_.push_back({scan, scan, travel_});
    }
    segments_.back().last_scan = scan;
    MergeVoxels(open_, scan_voxels);
}

void SegmentVoxelFile::Finish() {
    if (voxels_.size() < segments_.size()) WriteOpenSegment();
}

void SegmentVoxelFile::WriteOpenSegment() {
    records_.Append(open_.bytes.data(), open_.bytes.size());
    voxels_.push_back(open_.size);
    open_ = PackedVoxels{};
}

PackedVoxels SegmentVoxelFile::Load(std::size_t s) const {
    PackedVoxels set;
    set.size = voxels_.at(s);
    set.bytes = records_.Read(s);
    return set;
}

}  // namespace revisit
