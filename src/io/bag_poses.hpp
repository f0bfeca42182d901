#pragma once
/// Poses from a recording's pose topics paired with its scans by time stamp, and static transforms.
#include <Eigen/Geometry>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "io/ros_messages.hpp"

namespace revisit {

/// One topic's poses sorted by stamp (stable: equal stamps keep their recording order).
class PoseSeries {
  public:
    void Add(const PoseMsg& pose) { poses_.push_back(pose); }
    void Clear() { poses_.clear(); }
    void Sort();
    bool empty() const { return poses_.empty(); }
    std::size_t size() const { return poses_.size(); }
    const std::vector<PoseMsg>& poses() const { return poses_; }

    /// The odometry prior at `t`: the latest pose at or before it, interpolated toward the next one
    /// when there is one; none before the first pose.
    std::optional<PoseMsg> Prior(std::int64_t t_ns) const;
    /// The reference at `t`: exact, else interpolated when the poses either side are both within
    /// `tolerance_ns` (the cubic of core/pose_interpolation.hpp, its outer neighbours used when no
    /// farther than twice the tolerance from theirs), else the nearer one within it, else none.
    std::optional<PoseMsg> Reference(std::int64_t t_ns, std::int64_t tolerance_ns) const;

  private:
    std::vector<PoseMsg> poses_;
};

/// Static transforms (tf_static) as a tree of frames.
class StaticFrames {
  public:
    void Add(const PoseMsg& transform) { edges_.push_back(transform); }
    /// T_from_to through the edges (either direction), or none when the frames are not connected.
    std::optional<Eigen::Isometry3d> Find(const std::string& from, const std::string& to) const;
    bool empty() const { return edges_.empty(); }

  private:
    std::vector<PoseMsg> edges_;  ///< T_frame_child
};

}  // namespace revisit
