#include "core/pose_interpolation.hpp"

namespace revisit {

Eigen::Isometry3d InterpolatePose(const Eigen::Isometry3d& T_a, const Eigen::Isometry3d& T_b, double s) {
    const Eigen::Quaterniond q_a(T_a.linear());
    const Eigen::Quaterniond q_b(T_b.linear());
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = q_a.slerp(s, q_b).normalized().toRotationMatrix();  // Eigen's slerp takes the shorter arc
    T.translation() = (1.0 - s) * T_a.translation() + s * T_b.translation();
    return T;
}

Eigen::Isometry3d InterpolatePoseCubic(const StampedPose& before, const StampedPose& a, const StampedPose& b,
                                       const StampedPose& after, double t) {
    const double dt = b.t - a.t;
    const double s = (t - a.t) / dt;
    Eigen::Isometry3d T = InterpolatePose(*a.T, *b.T, s);
    // Each end's velocity: the slope at that pose of the parabola through it and its two neighbours
    // (the secants weighted by the other side's spacing), exact for uniformly accelerated motion at
    // any spacing; the segment's secant where a neighbour is missing.
    const Eigen::Vector3d p_a = a.T->translation(), p_b = b.T->translation();
    const Eigen::Vector3d secant = (p_b - p_a) / dt;
    Eigen::Vector3d v_a = secant, v_b = secant;
    if (before.T) {
        const double h = a.t - before.t;
        v_a = ((p_a - before.T->translation()) / h * dt + secant * h) / (dt + h);
    }
    if (after.T) {
        const double h = after.t - b.t;
        v_b = (secant * h + (after.T->translation() - p_b) / h * dt) / (dt + h);
    }
    const double s2 = s * s, s3 = s2 * s;
    T.translation() = (2 * s3 - 3 * s2 + 1) * p_a + (s3 - 2 * s2 + s) * dt * v_a + (-2 * s3 + 3 * s2) * p_b + (s3 - s2) * dt * v_b;
    return T;
}

}  // namespace revisit
