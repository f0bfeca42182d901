#include "core/se3.hpp"

#include <Eigen/SVD>
#include <algorithm>
#include <cmath>

namespace revisit {
namespace {
Eigen::Matrix3d Hat(const Eigen::Vector3d& v) {
    Eigen::Matrix3d m;
    m << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
    return m;
}
constexpr double kSmallAngle = 1e-10;
}  // namespace

Eigen::Matrix3d ExpSO3(const Eigen::Vector3d& phi) {
    const double angle = phi.norm();
    if (angle < kSmallAngle) return Eigen::Matrix3d::Identity() + Hat(phi);
    return Eigen::AngleAxisd(angle, phi / angle).toRotationMatrix();
}

Eigen::Vector3d LogSO3(const Eigen::Matrix3d& R) {
    const Eigen::AngleAxisd aa(R);
    return aa.angle() * aa.axis();
}

Eigen::Matrix3d LeftJacobianSO3(const Eigen::Vector3d& phi) {
    const double angle = phi.norm();
    const Eigen::Matrix3d K = Hat(phi);
    if (angle < 1e-6) return Eigen::Matrix3d::Identity() + 0.5 * K + K * K / 6.0;
    const double a2 = angle * angle;
    return Eigen::Matrix3d::Identity() + (1.0 - std::cos(angle)) / a2 * K +
           (angle - std::sin(angle)) / (a2 * angle) * K * K;
}

Eigen::Isometry3d ExpSE3(const Vector6d& xi) {
    const Eigen::Vector3d rho = xi.head<3>();
    const Eigen::Vector3d phi = xi.tail<3>();
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = ExpSO3(phi);
    T.translation() = LeftJacobianSO3(phi) * rho;
    return T;
}

Vector6d LogSE3(const Eigen::Isometry3d& T) {
    const Eigen::Vector3d phi = LogSO3(T.linear());
    Vector6d xi;
    xi.head<3>() = LeftJacobianSO3(phi).inverse() * T.translation();
    xi.tail<3>() = phi;
    return xi;
}

Eigen::Isometry3d PoseFromXYZRPY(double x, double y, double z, double roll, double pitch, double yaw) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) *
                  Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) *
                  Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()))
                     .toRotationMatrix();
    T.translation() = Eigen::Vector3d(x, y, z);
    return T;
}

double RotationAngle(const Eigen::Isometry3d& T) {
    // Clamp: rounding can push the trace argument slightly outside [-1, 1].
    const double c = std::clamp((T.linear().trace() - 1.0) / 2.0, -1.0, 1.0);
    return std::acos(c);
}

Eigen::Matrix3d NearestRotation(const Eigen::Matrix3d& M) {
    Eigen::JacobiSVD<Eigen::Matrix3d> svd(M, Eigen::ComputeFullU | Eigen::ComputeFullV);
    Eigen::Matrix3d D = Eigen::Matrix3d::Identity();
    D(2, 2) = (svd.matrixU() * svd.matrixV().transpose()).determinant() < 0 ? -1.0 : 1.0;
    return svd.matrixU() * D * svd.matrixV().transpose();
}

}  // namespace revisit
