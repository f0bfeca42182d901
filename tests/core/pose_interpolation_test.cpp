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

namespace revisit {
namespace {

/// Uniformly accelerated motion with a turn, sampled at uneven times: what a reference at another
/// rate than the scans looks like between its poses.
Eigen::Isometry3d Accelerating(double t) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = Eigen::AngleAxisd(0.3 * t, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    T.translation() = Eigen::Vector3d(1.0 + 2.0 * t + 0.7 * t * t, -0.4 * t * t, 0.1 * t);
    return T;
}

TEST(PoseInterpolationCubic, FollowsAcceleratedMotionAtUnevenSpacing) {
    const double times[4] = {0.0, 0.35, 1.6, 1.9};  // spacings 0.35, 1.25, 0.3 s
    Eigen::Isometry3d poses[4];
    for (int i = 0; i < 4; ++i) poses[i] = Accelerating(times[i]);
    const StampedPose before{times[0], &poses[0]}, a{times[1], &poses[1]}, b{times[2], &poses[2]}, after{times[3], &poses[3]};
    double worst_cubic = 0.0, worst_linear = 0.0;
    for (double t = times[1]; t <= times[2]; t += 0.05) {
        const Eigen::Vector3d truth = Accelerating(t).translation();
        const double s = (t - times[1]) / (times[2] - times[1]);
        worst_cubic = std::max(worst_cubic, (InterpolatePoseCubic(before, a, b, after, t).translation() - truth).norm());
        worst_linear = std::max(worst_linear, (InterpolatePose(poses[1], poses[2], s).translation() - truth).norm());
        // The rotation is the slerp's, whatever the neighbours.
        EXPECT_TRUE(InterpolatePoseCubic(before, a, b, after, t).linear().isApprox(InterpolatePose(poses[1], poses[2], s).linear(), 1e-12));
    }
    EXPECT_LT(worst_cubic, 1e-9);  // a parabola is reproduced exactly
    EXPECT_GT(worst_linear, 0.1);  // a straight segment cuts the curve
    // Exact at the poses.
    EXPECT_LT((InterpolatePoseCubic(before, a, b, after, times[1]).translation() - poses[1].translation()).norm(), 1e-12);
    EXPECT_LT((InterpolatePoseCubic(before, a, b, after, times[2]).translation() - poses[2].translation()).norm(), 1e-12);
}

TEST(PoseInterpolationCubic, WithoutNeighboursIsTheStraightSegment) {
    const Eigen::Isometry3d p0 = Accelerating(0.0), p1 = Accelerating(1.0);
    const StampedPose none, a{0.0, &p0}, b{1.0, &p1};
    for (const double t : {0.0, 0.25, 0.5, 0.9, 1.0}) {
        EXPECT_TRUE(InterpolatePoseCubic(none, a, b, none, t).isApprox(InterpolatePose(p0, p1, t), 1e-12)) << t;
    }
}

}  // namespace
}  // namespace revisit
