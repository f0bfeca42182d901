#pragma once
/// Poses between two stamped poses: what a reference or a pose file says at a scan's time stamp.
#include <Eigen/Geometry>

namespace revisit {

/// The pose a fraction `s` of the way from T_a (s = 0) to T_b (s = 1): rotation by slerp along the
/// shorter arc, translation linearly (the two are interpolated apart, as trajectory tools do for
/// reference poses; not the SE(3) geodesic, which bends the path of a turning vehicle's position).
Eigen::Isometry3d InterpolatePose(const Eigen::Isometry3d& T_a, const Eigen::Isometry3d& T_b, double s);

/// A stamped pose, for the cubic interpolation's neighbours.
struct StampedPose {
    double t = 0.0;  ///< [s]
    const Eigen::Isometry3d* T = nullptr;
};

/// The pose at time t in [a.t, b.t]: the rotation by slerp as above; the translation by a cubic
/// Hermite curve through a and b whose velocities come from the neighbours `before` (ahead of a)
/// and `after` (past b) where they are given (T non-null), else from a..b alone. A
/// reference sampled more sparsely than the scans (a walk's key frames, a slow GNSS) bends between
/// its poses; a straight segment cuts the curve by up to a centimetre or more, the cubic follows it
/// (exact at the poses, continuous in velocity across them, exact for uniformly accelerated motion).
Eigen::Isometry3d InterpolatePoseCubic(const StampedPose& before, const StampedPose& a, const StampedPose& b,
                                       const StampedPose& after, double t);

}  // namespace revisit
