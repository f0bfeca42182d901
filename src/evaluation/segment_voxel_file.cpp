#include "evaluation/segment_voxel_file.hpp"

#include "core/error.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <string>

namespace revisit {
namespace {

std::string Problem(const std::string& what) { return what + ": " + std::strerror(errno); }

}  // namespace

SegmentVoxelFile::SegmentVoxelFile(const std::filesystem::path& file, double segment_length)
    : scratch_(file), segment_length_(segment_length) {
    if (!(segment_length > 0.0)) throw ConfigError("ground truth: segment_length must be positive");
    read_fd_ = ::open(scratch_.path().c_str(), O_RDONLY | O_CLOEXEC | O_NOFOLLOW);
    if (read_fd_ < 0) throw DatasetError(scratch_.path(), Problem("cannot read back the scratch file of segment voxel sets"));
}

SegmentVoxelFile::~SegmentVoxelFile() {
    if (read_fd_ >= 0) ::close(read_fd_);
}

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
    if (stored_.size() < segments_.size()) WriteOpenSegment();
}

void SegmentVoxelFile::WriteOpenSegment() {
    const auto* data = reinterpret_cast<const char*>(open_.bytes.data());
    const std::size_t bytes = open_.bytes.size();
    for (std::size_t written = 0; written < bytes;) {
        const ssize_t n = ::pwrite(scratch_.descriptor(), data + written, bytes - written, off_t(end_ + written));
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) throw DatasetError(scratch_.path(), Problem("cannot write a segment's voxel set"));
        written += std::size_t(n);
    }
    stored_.push_back({end_, bytes, open_.size});
    end_ += bytes;
    open_ = PackedVoxels{};
}

PackedVoxels SegmentVoxelFile::Load(std::size_t s) const {
    const Stored& stored = stored_.at(s);
    PackedVoxels set;
    set.size = stored.voxels;
    set.bytes.resize(stored.bytes);
    auto* data = reinterpret_cast<char*>(set.bytes.data());
    for (std::size_t read = 0; read < stored.bytes;) {
        const ssize_t n = ::pread(read_fd_, data + read, stored.bytes - read, off_t(stored.offset + read));
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) throw DatasetError(scratch_.path(), Problem("cannot read back segment " + std::to_string(s) + "'s voxel set"));
        read += std::size_t(n);
    }
    return set;
}

}  // namespace revisit
