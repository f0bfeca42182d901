#include "io/timed_poses.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/pose_interpolation.hpp"

namespace revisit {
namespace {
/// [s] rounded to the microsecond for messages: absolute stamps keep their digits, spacings lose
/// the float noise of their sums (0.349857 instead of 0.349856500000001).
double Micro(double seconds) { return std::round(seconds * 1e6) / 1e6; }
}  // namespace

double MedianSpacing(const std::vector<double>& times) {
    std::vector<double> spacing;
    for (std::size_t i = 1; i < times.size(); ++i) {
        if (times[i] > times[i - 1]) spacing.push_back(times[i] - times[i - 1]);
    }
    if (spacing.empty()) return 0.0;
    const auto middle = spacing.begin() + static_cast<long>(spacing.size() / 2);
    std::nth_element(spacing.begin(), middle, spacing.end());
    return *middle;
}

TimedPoses::TimedPoses(Trajectory trajectory, const TimePairingConfig& config) : trajectory_(std::move(trajectory)) {
    const double spacing = MedianSpacing(trajectory_.timestamps);
    end_tolerance_ = config.end_tolerance > 0.0 ? config.end_tolerance : 0.5 * spacing;
    max_gap_ = config.max_gap > 0.0 ? config.max_gap : 5.0 * spacing;
}

std::optional<Eigen::Isometry3d> TimedPoses::At(double t) const {
    const auto& times = trajectory_.timestamps;
    if (times.empty() || !(t >= first_time() - end_tolerance_) || !(t <= last_time() + end_tolerance_)) return std::nullopt;
    if (t <= first_time()) return trajectory_.poses.front();
    if (t >= last_time()) return trajectory_.poses.back();
    // times[after - 1] <= t < times[after]: the two neighbours (equal stamps: the later of the run).
    const auto after = static_cast<std::size_t>(std::upper_bound(times.begin(), times.end(), t) - times.begin());
    const std::size_t before = after - 1;
    if (times[before] == t) return trajectory_.poses[before];
    const double gap = times[after] - times[before];
    if (gap > max_gap_) return std::nullopt;
    // The neighbours outside the segment shape the curve only when they are not across a gap.
    const auto& poses = trajectory_.poses;
    StampedPose previous, next;
    if (before > 0 && times[before] - times[before - 1] <= max_gap_ && times[before] > times[before - 1]) {
        previous = {times[before - 1], &poses[before - 1]};
    }
    if (after + 1 < times.size() && times[after + 1] - times[after] <= max_gap_ && times[after + 1] > times[after]) {
        next = {times[after + 1], &poses[after + 1]};
    }
    return InterpolatePoseCubic(previous, {times[before], &poses[before]}, {times[after], &poses[after]}, next, t);
}

std::string TimedPoses::DescribeSpan() const {
    std::ostringstream out;
    out.precision(15);
    out << "t = " << Micro(first_time()) << " .. " << Micro(last_time()) << " s (" << size() << " poses; end tolerance "
        << Micro(end_tolerance_) << " s, gaps up to " << Micro(max_gap_) << " s interpolated)";
    return out.str();
}

void UnpairedScans::Add(std::size_t index, double timestamp) {
    if (count == 0) first_index = index, first_time = timestamp;
    last_index = index, last_time = timestamp;
    ++count;
}

std::string UnpairedScans::Describe() const {
    if (count == 0) return {};
    std::ostringstream out;
    out.precision(15);
    out << count << (count == 1 ? " scan has" : " scans have") << " no reference pose (outside the reference's time span "
        << "or in a gap of it; left out of the metrics): first scan " << first_index << " at t = " << Micro(first_time) << " s";
    if (count > 1) out << ", last scan " << last_index << " at t = " << Micro(last_time) << " s";
    return out.str();
}

}  // namespace revisit
