#include <gtest/gtest.h>

#include <random>

#include "core/se3.hpp"
#include "core/trajectory.hpp"

namespace revisit {
namespace {

TEST(Se3, ExpOfLogIsIdentityMapForRandomPoses) {
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(-3.0, 3.0);
    for (int i = 0; i < 200; ++i) {
        const auto T = PoseFromXYZRPY(u(rng), u(rng), u(rng), u(rng) / 2, u(rng) / 4, u(rng));
        const auto T_back = ExpSE3(LogSE3(T));
        EXPECT_LT((T.matrix() - T_back.matrix()).norm(), 1e-9);
    }
}

TEST(Se3, SmallAnglesAreExact) {
    Vector6d xi;
    xi << 1.0, 2.0, 3.0, 1e-12, -2e-12, 0.0;
    const auto T = ExpSE3(xi);
    EXPECT_NEAR((T.translation() - Eigen::Vector3d(1, 2, 3)).norm(), 0.0, 1e-9);
    EXPECT_NEAR(RotationAngle(T), 0.0, 1e-9);
}

TEST(Se3, PureRotationAboutZMatchesYaw) {
    const auto T = PoseFromXYZRPY(0, 0, 0, 0, 0, 0.3);
    EXPECT_NEAR(RotationAngle(T), 0.3, 1e-12);
    EXPECT_NEAR(LogSE3(T)(5), 0.3, 1e-12);
}

TEST(Se3, NearestRotationCleansRoundedMatrices) {
    Eigen::Matrix3d R = PoseFromXYZRPY(0, 0, 0, 0.1, 0.2, 0.3).linear();
    R(0, 0) += 1e-4;
    const Eigen::Matrix3d clean = NearestRotation(R);
    EXPECT_NEAR((clean * clean.transpose() - Eigen::Matrix3d::Identity()).norm(), 0.0, 1e-12);
    EXPECT_NEAR(clean.determinant(), 1.0, 1e-12);
    EXPECT_LT((clean - R).norm(), 2e-4);
}

TEST(Trajectory, CumulativeDistanceAddsSteps) {
    Poses poses(3, Eigen::Isometry3d::Identity());
    poses[1].translation() = Eigen::Vector3d(3, 4, 0);
    poses[2].translation() = Eigen::Vector3d(3, 4, 2);
    const auto d = CumulativeDistance(poses);
    ASSERT_EQ(d.size(), 3u);
    EXPECT_DOUBLE_EQ(d[1], 5.0);
    EXPECT_DOUBLE_EQ(d[2], 7.0);
    EXPECT_DOUBLE_EQ(PathLength(poses), 7.0);
    EXPECT_DOUBLE_EQ(PathLength({}), 0.0);
}

}  // namespace
}  // namespace revisit
