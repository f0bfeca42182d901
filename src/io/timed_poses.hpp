#pragma once
/// Pairing a stamped trajectory (a TUM reference or pose file) with scans by time stamp, at any rate:
/// the pose at a scan's stamp is interpolated between the two neighbouring poses; a scan outside the
/// poses' span (beyond a small tolerance) or inside a gap gets none, never the wrong one.
#include <cstddef>
#include <optional>
#include <string>

#include "core/trajectory.hpp"

namespace revisit {

struct TimePairingConfig {
    /// [s] how far before the first or after the last pose a scan may lie and still take that end
    /// pose (no extrapolation); 0: half the median spacing of the file's poses.
    double end_tolerance = 0.0;
    /// [s] the longest time between two poses that a scan's pose is interpolated across; a scan in a
    /// longer gap has none. 0: 5 x the median spacing of the file's poses.
    double max_gap = 0.0;
};

class TimedPoses {
  public:
    /// `trajectory` needs one time stamp per pose, never decreasing (ReadTumPoses checks both).
    TimedPoses(Trajectory trajectory, const TimePairingConfig& config);

    /// The pose at time t [s], or nullopt when t is outside [first - tolerance, last + tolerance] or
    /// between two poses farther apart than max_gap.
    std::optional<Eigen::Isometry3d> At(double t) const;

    double first_time() const { return trajectory_.timestamps.front(); }
    double last_time() const { return trajectory_.timestamps.back(); }
    double end_tolerance() const { return end_tolerance_; }
    double max_gap() const { return max_gap_; }
    std::size_t size() const { return trajectory_.size(); }
    /// "t = FIRST .. LAST s (N poses; end tolerance E s, gaps up to G s interpolated)".
    std::string DescribeSpan() const;

  private:
    Trajectory trajectory_;
    double end_tolerance_ = 0.0;
    double max_gap_ = 0.0;
};

/// Median of the positive differences between consecutive times [s]; 0 when there are none.
double MedianSpacing(const std::vector<double>& times);

/// Scans that got no pose from a reference, for one line at the end of a run.
struct UnpairedScans {
    std::size_t count = 0;
    std::size_t first_index = 0, last_index = 0;  ///< dataset scan indices
    double first_time = 0.0, last_time = 0.0;     ///< [s]

    void Add(std::size_t index, double timestamp);
    /// "N scans have no reference pose (first: scan I at t = T s, last: ...)"; empty when count is 0.
    std::string Describe() const;
};

}  // namespace revisit
