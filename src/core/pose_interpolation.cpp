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

}  // namespace revisit
