#include "io/bag_poses.hpp"

#include "core/pose_interpolation.hpp"

#include <algorithm>
#include <map>
#include <queue>

namespace revisit {

void PoseSeries::Sort() {
    std::stable_sort(poses_.begin(), poses_.end(),
                     [](const PoseMsg& a, const PoseMsg& b) { return a.stamp_ns < b.stamp_ns; });
}

namespace {
/// The first pose after t.
std::vector<PoseMsg>::const_iterator After(const std::vector<PoseMsg>& poses, std::int64_t t) {
    return std::upper_bound(poses.begin(), poses.end(), t, [](std::int64_t v, const PoseMsg& p) { return v < p.stamp_ns; });
}

PoseMsg Between(const PoseMsg& a, const PoseMsg& b, std::int64_t t) {
    PoseMsg pose = a;
    pose.stamp_ns = t;
    pose.T = InterpolatePose(a.T, b.T, double(t - a.stamp_ns) / double(b.stamp_ns - a.stamp_ns));
    return pose;
}

double Seconds(std::int64_t ns) { return double(ns) * 1e-9; }
}  // namespace

std::optional<PoseMsg> PoseSeries::Prior(std::int64_t t) const {
    const auto next = After(poses_, t);
    if (next == poses_.begin()) return std::nullopt;
    const PoseMsg& before = *std::prev(next);
    if (before.stamp_ns == t || next == poses_.end()) return before;
    return Between(before, *next, t);
}

std::optional<PoseMsg> PoseSeries::Reference(std::int64_t t, std::int64_t tolerance) const {
    const auto next = After(poses_, t);
    const PoseMsg* before = next == poses_.begin() ? nullptr : &*std::prev(next);
    if (before && before->stamp_ns == t) return *before;
    const bool before_ok = before && t - before->stamp_ns <= tolerance;
    const bool next_ok = next != poses_.end() && next->stamp_ns - t <= tolerance;
    if (before_ok && next_ok) {
        // Stamps relative to t keep the nanoseconds that seconds since 1970 would round away.
        const auto at = [t](const PoseMsg& p) { return StampedPose{Seconds(p.stamp_ns - t), &p.T}; };
        StampedPose previous, following;
        if (before != &poses_.front() && before->stamp_ns - std::prev(before)->stamp_ns <= 2 * tolerance &&
            std::prev(before)->stamp_ns < before->stamp_ns) {
            previous = at(*std::prev(before));
        }
        if (std::next(next) != poses_.end() && std::next(next)->stamp_ns - next->stamp_ns <= 2 * tolerance &&
            std::next(next)->stamp_ns > next->stamp_ns) {
            following = at(*std::next(next));
        }
        PoseMsg pose = *before;
        pose.stamp_ns = t;
        pose.T = InterpolatePoseCubic(previous, at(*before), at(*next), following, 0.0);
        return pose;
    }
    if (before_ok) return *before;
    if (next_ok) return *next;
    return std::nullopt;
}

std::optional<Eigen::Isometry3d> StaticFrames::Find(const std::string& from, const std::string& to) const {
    if (from == to) return Eigen::Isometry3d::Identity();
    // Breadth-first over the edges both ways: the tree is a handful of frames.
    std::map<std::string, Eigen::Isometry3d> T_from;
    T_from[from] = Eigen::Isometry3d::Identity();
    std::queue<std::string> open;
    open.push(from);
    while (!open.empty()) {
        const std::string frame = open.front();
        open.pop();
        const Eigen::Isometry3d T_from_frame = T_from.at(frame);
        for (const auto& edge : edges_) {
            std::string other;
            Eigen::Isometry3d T_frame_other;
            if (edge.frame_id == frame) {
                other = edge.child_frame_id, T_frame_other = edge.T;
            } else if (edge.child_frame_id == frame) {
                other = edge.frame_id, T_frame_other = edge.T.inverse();
            } else {
                continue;
            }
            if (T_from.count(other)) continue;
            T_from[other] = T_from_frame * T_frame_other;
            if (other == to) return T_from[other];
            open.push(other);
        }
    }
    return std::nullopt;
}

}  // namespace revisit
