#include "pipeline/pose_file_source.hpp"

#include <cmath>
#include <sstream>

#include "core/error.hpp"
#include "io/trajectory_io.hpp"

namespace revisit {

PoseFileSource::PoseFileSource(const std::filesystem::path& file, std::string option, const TimePairingConfig& pairing)
    : file_(file), option_(std::move(option)) {
    if (file.empty()) return;
    Trajectory trajectory = ReadPoses(file);
    if (trajectory.has_timestamps()) timed_.emplace(std::move(trajectory), pairing);
    else by_index_ = std::move(trajectory.poses);
}

void PoseFileSource::CheckCount(std::optional<std::size_t> num_scans) const {
    if (!active() || by_time() || !num_scans || by_index_.size() == *num_scans) return;
    throw DatasetError(file_, option_ + " has " + std::to_string(by_index_.size()) + " poses for " + std::to_string(*num_scans) +
                                  " scans (KITTI poses have no times: they pair with scans by index, one per scan)");
}

std::optional<Eigen::Isometry3d> PoseFileSource::At(std::size_t index, double timestamp) const {
    if (timed_) return timed_->At(timestamp);
    if (index >= by_index_.size()) {
        throw DatasetError(file_, option_ + " has " + std::to_string(by_index_.size()) + " poses; scan " + std::to_string(index) +
                                      " has none (KITTI poses have no times: they pair with scans by index, one per scan)");
    }
    return by_index_[index];
}

Eigen::Isometry3d PoseFileSource::Required(std::size_t index, double timestamp) const {
    if (auto pose = At(index, timestamp)) return *pose;
    std::ostringstream problem;
    problem.precision(15);
    problem << option_ << " (TUM, paired by time stamp): scan " << index << " at t = " << std::round(timestamp * 1e6) / 1e6
            << " s is outside the file's poses or in a gap of them, " << timed_->DescribeSpan()
            << "; every scan needs a pose (input.reference_end_tolerance / input.reference_max_gap widen the pairing)";
    throw DatasetError(file_, problem.str());
}

std::string PoseFileSource::DescribeSpan() const {
    return timed_ ? timed_->DescribeSpan() : std::to_string(by_index_.size()) + " poses by index";
}

}  // namespace revisit
