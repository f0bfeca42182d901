#include "evaluation/segment_voxel_file.hpp"

#include "core/error.hpp"

#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>

namespace revisit {
namespace {

double PositiveLength(double segment_length) {
    if (!(segment_length > 0.0)) throw ConfigError("ground truth: segment_length must be positive");
    return segment_length;
}

/// x0, y0 (4 bytes each), size (8), bounded (1), then the cells (4 each), host byte order: the file
/// is this process's own scratch.
constexpr std::size_t kColumnsHeader = 4 + 4 + 8 + 1;

std::vector<std::uint8_t> ColumnsRecord(const VoxelColumns& columns) {
    std::vector<std::uint8_t> bytes(kColumnsHeader + 4 * columns.cells.size());
    const std::uint64_t size = columns.size;
    const std::uint8_t bounded = columns.bounded ? 1 : 0;
    std::memcpy(bytes.data(), &columns.x0, 4);
    std::memcpy(bytes.data() + 4, &columns.y0, 4);
    std::memcpy(bytes.data() + 8, &size, 8);
    std::memcpy(bytes.data() + 16, &bounded, 1);
    if (!columns.cells.empty()) std::memcpy(bytes.data() + kColumnsHeader, columns.cells.data(), 4 * columns.cells.size());
    return bytes;
}

}  // namespace

SegmentVoxelFile::SegmentVoxelFile(const std::filesystem::path& file, double segment_length)
    : records_(file, "segment voxel set"),
      columns_(std::filesystem::path(file).replace_extension(".columns.scratch"), "segment voxel columns"),
      cutter_(PositiveLength(segment_length)) {}

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
    const std::vector<std::uint8_t> columns = ColumnsRecord(ColumnsOf(open_));
    columns_.Append(columns.data(), columns.size());
    voxels_.push_back(open_.size);
    open_ = PackedVoxels{};
}

PackedVoxels SegmentVoxelFile::Load(std::size_t s) const {
    PackedVoxels set;
    set.size = voxels_.at(s);
    set.bytes = records_.Read(s);
    return set;
}

VoxelColumns SegmentVoxelFile::LoadColumns(std::size_t s) const {
    const std::vector<std::uint8_t> bytes = columns_.Read(s);
    VoxelColumns columns;
    // ScratchRecords returns each record as appended: a length that is not a whole record is damage.
    if (bytes.size() < kColumnsHeader || (bytes.size() - kColumnsHeader) % 4 != 0)
        throw DatasetError(columns_.path(), "segment voxel columns " + std::to_string(s) + ": a scratch record of " + std::to_string(bytes.size()) + " bytes");
    std::uint64_t size = 0;
    std::memcpy(&columns.x0, bytes.data(), 4);
    std::memcpy(&columns.y0, bytes.data() + 4, 4);
    std::memcpy(&size, bytes.data() + 8, 8);
    columns.size = static_cast<std::size_t>(size);
    columns.bounded = bytes[16] != 0;
    columns.cells.resize((bytes.size() - kColumnsHeader) / 4);
    if (!columns.cells.empty()) std::memcpy(columns.cells.data(), bytes.data() + kColumnsHeader, bytes.size() - kColumnsHeader);
    return columns;
}

}  // namespace revisit
