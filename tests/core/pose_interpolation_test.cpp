#include <gtest/gtest.h>

#include <cmath>

#include "core/pose_interpolation.hpp"
#include "core/se3.hpp"

namespace revisit {
namespace {

TEST(PoseInterpolation, EndsAreTheGivenPoses) {
    const Eigen::Isometry3d a = PoseFromXYZRPY(1, 2, 3, 0.1, -0.2, 0.3);
    const Eigen::Isometry3d b = PoseFromXYZRPY(-4, 5, 0.5, -0.3, 0.1, 2.5);
    EXPECT_LT((InterpolatePose(a, b, 0.0).matrix() - a.matrix()).norm(), 1e-12);
    EXPECT_LT((InterpolatePose(a, b, 1.0).matrix() - b.matrix()).norm(), 1e-12);
}

TEST(PoseInterpolation, RotationBySlerpTranslationLinearly) {
    const Eigen::Isometry3d a = PoseFromXYZRPY(0, 0, 0, 0, 0, 0.2);
    const Eigen::Isometry3d b = PoseFromXYZRPY(10, -2, 1, 0, 0, 1.8);
    const Eigen::Isometry3d T = InterpolatePose(a, b, 0.25);
    EXPECT_LT((T.translation() - Eigen::Vector3d(2.5, -0.5, 0.25)).norm(), 1e-12);
    // About one axis, slerp is a constant rate in angle: yaw 0.2 + 0.25 * 1.6.
    EXPECT_LT((T.linear() - PoseFromXYZRPY(0, 0, 0, 0, 0, 0.6).linear()).norm(), 1e-12);
}

TEST(PoseInterpolation, TakesTheShorterArc) {
    // Yaw 170 deg to -170 deg: 20 deg apart through 180, not 340 through 0.
    const double deg = M_PI / 180.0;
    const Eigen::Isometry3d a = PoseFromXYZRPY(0, 0, 0, 0, 0, 170 * deg);
    const Eigen::Isometry3d b = PoseFromXYZRPY(0, 0, 0, 0, 0, -170 * deg);
    const Eigen::Isometry3d T = InterpolatePose(a, b, 0.5);
    EXPECT_NEAR(RotationAngle(T), M_PI, 1e-9);
    // A general rotation: the midpoint is half the relative rotation from each end.
    const Eigen::Isometry3d c = PoseFromXYZRPY(0, 0, 0, 0.4, -0.3, 1.0);
    const Eigen::Isometry3d mid = InterpolatePose(a, c, 0.5);
    EXPECT_NEAR(RotationAngle(a.inverse() * mid), 0.5 * RotationAngle(a.inverse() * c), 1e-9);
    EXPECT_NEAR(RotationAngle(mid.inverse() * c), 0.5 * RotationAngle(a.inverse() * c), 1e-9);
}

}  // namespace
}  // namespace revisit
