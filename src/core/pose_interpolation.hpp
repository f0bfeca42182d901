#pragma once
/// Poses between two stamped poses: what a reference or a pose file says at a scan's time stamp.
#include <Eigen/Geometry>

namespace revisit {

/// The pose a fraction `s` of the way from T_a (s = 0) to T_b (s = 1): rotation by slerp along the
/// shorter arc, translation linearly (the two are interpolated apart, as trajectory tools do for
/// reference poses; not the SE(3) geodesic, which bends the path of a turning vehicle's position).
Eigen::Isometry3d InterpolatePose(const Eigen::Isometry3d& T_a, const Eigen::Isometry3d& T_b, double s);

}  // namespace revisit
