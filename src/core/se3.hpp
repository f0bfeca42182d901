#pragma once
/// SE(3) exponential and logarithm on Eigen types (no Sophus in Debian bookworm).
/// Tangent ordering: [translation rho (3); rotation phi (3)], as in Barfoot,
/// "State Estimation for Robotics", Eq. (7.85)-(7.86).
#include <Eigen/Core>
#include <Eigen/Geometry>

namespace revisit {

using Vector6d = Eigen::Matrix<double, 6, 1>;

/// Rotation matrix of the axis-angle vector phi (Rodrigues); exact near zero.
Eigen::Matrix3d ExpSO3(const Eigen::Vector3d& phi);
/// Axis-angle vector of a rotation matrix; |phi| in [0, pi].
Eigen::Vector3d LogSO3(const Eigen::Matrix3d& R);
/// Left Jacobian of SO(3), Barfoot Eq. (7.77).
Eigen::Matrix3d LeftJacobianSO3(const Eigen::Vector3d& phi);

Eigen::Isometry3d ExpSE3(const Vector6d& xi);
Vector6d LogSE3(const Eigen::Isometry3d& T);

/// Pose from x, y, z [m] and roll, pitch, yaw [rad] (Z-Y-X order: R = Rz(yaw) Ry(pitch) Rx(roll)).
Eigen::Isometry3d PoseFromXYZRPY(double x, double y, double z, double roll, double pitch, double yaw);

/// Rotation angle of a pose [rad], in [0, pi].
double RotationAngle(const Eigen::Isometry3d& T);

/// The closest proper rotation to M (SVD); used to clean rotations read from text files.
Eigen::Matrix3d NearestRotation(const Eigen::Matrix3d& M);

}  // namespace revisit
