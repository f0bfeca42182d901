#pragma once
/// A trajectory file given on the command line (`--gt FILE`, `--poses FILE`) paired with the scans:
/// TUM files (with times) by time stamp, interpolated (io/timed_poses.hpp); KITTI files (no times)
/// by index, one pose per scan.
#include <filesystem>
#include <optional>
#include <string>

#include "core/trajectory.hpp"
#include "io/timed_poses.hpp"

namespace revisit {

class PoseFileSource {
  public:
    /// `option` names the file in messages ("--gt", "--poses"); an empty file is an inactive source.
    PoseFileSource(const std::filesystem::path& file, std::string option, const TimePairingConfig& pairing);

    bool active() const { return !file_.empty(); }
    bool by_time() const { return timed_.has_value(); }
    /// KITTI files: their pose count must be the dataset's scan count. Throws DatasetError naming the
    /// file and both counts; does nothing for TUM files or an unknown count.
    void CheckCount(std::optional<std::size_t> num_scans) const;
    /// The pose of scan `index` at `timestamp` [s]: TUM, interpolated, or nullopt outside the file's
    /// span or in a gap; KITTI, the index-th pose (an index past the file's end throws, naming the counts).
    std::optional<Eigen::Isometry3d> At(std::size_t index, double timestamp) const;
    /// Like At, but a scan without a pose is a DatasetError naming the scan and the file's span.
    Eigen::Isometry3d Required(std::size_t index, double timestamp) const;
    /// "t = A .. B s (...)" for TUM files, "N poses by index" for KITTI ones.
    std::string DescribeSpan() const;

  private:
    std::filesystem::path file_;
    std::string option_;
    std::optional<TimedPoses> timed_;
    Poses by_index_;
};

}  // namespace revisit
