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
    : records_(file, "segment voxel set"), cutter_(PositiveLength(segment_length)) {}

void SegmentVoxelFile::Add(const Eigen::Isometry3d& T_world_sensor, const PackedVoxels& scan_voxels) {
    // A new segment: the one before is complete.
    if (cutter_.Add(T_world_sensor.translation()) && cutter_.segments().size() > 1) WriteOpenSegment();
    MergeVoxels(open_, scan_voxels);
}

void SegmentVoxelFile::Finish() {
    if (voxels_.size() < cutter_.segments().size()) WriteOpenSegment();
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
