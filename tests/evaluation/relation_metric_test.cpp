#include "evaluation/relation_metric.hpp"

#include "core/error.hpp"
#include "core/se3.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

namespace revisit {
namespace {

constexpr double kPi = 3.14159265358979323846;

TEST(ParseRelations, ReadsFreiburgLinesAndSkipsComments) {
    std::istringstream text(
        "# t1 t2 x y z roll pitch yaw\n"
        "100.5 101.25 1.0 0.5 0 0 0 0.1\n"
        "\n"
        "  101.25 102.0 -0.2 0 0 0 0 -3.0\r\n");
    const auto relations = ParseRelations(text, "fixture.relations");
    ASSERT_EQ(relations.size(), 2u);
    EXPECT_DOUBLE_EQ(relations[0].t1, 100.5);
    EXPECT_DOUBLE_EQ(relations[0].t2, 101.25);
    EXPECT_NEAR((relations[0].T_1_2.translation() - Eigen::Vector3d(1.0, 0.5, 0.0)).norm(), 0.0, 1e-12);
    EXPECT_NEAR(std::atan2(relations[1].T_1_2(1, 0), relations[1].T_1_2(0, 0)), -3.0, 1e-12);
}

TEST(ParseRelations, NamesFileAndLineOfBadInput) {
    std::istringstream text("1 2 0 0 0 0 0 0\n1 2 0 0 zero 0 0 0\n");
    try {
        ParseRelations(text, "bad.relations");
        FAIL() << "expected DatasetError";
    } catch (const DatasetError& error) {
        EXPECT_EQ(error.line(), 2u);
        EXPECT_NE(std::string(error.what()).find("bad.relations:2"), std::string::npos);
    }
}

TEST(EvaluateRelations, HandComputedErrors) {
    // Trajectory along x with 1 m steps, except the step 1 -> 2 is 1.1 m.
    Trajectory trajectory;
    trajectory.timestamps = {0.0, 1.0, 2.0, 3.0};
    trajectory.poses = {PoseFromXYZRPY(0, 0, 0, 0, 0, 0), PoseFromXYZRPY(1, 0, 0, 0, 0, 0),
                        PoseFromXYZRPY(2.1, 0, 0, 0, 0, 0), PoseFromXYZRPY(3.1, 0, 0, 0, 0, 0)};
    std::istringstream text(
        "0.0 1.0 1 0 0 0 0 0\n"          // exact: 0 m, 0 deg
        "1.0004 2.0 1 0 0 0 0 0\n"       // stamp within 1 ms; 0.1 m off
        "2.0 3.0 1 0 0 0 0 0.1\n"        // the log says it turned 0.1 rad; trajectory did not
        "3.0 7.0 1 0 0 0 0 0\n");        // no pose at 7 s
    const auto errors = EvaluateRelations(trajectory, ParseRelations(text, "r"));
    EXPECT_EQ(errors.num_used, 3u);
    EXPECT_EQ(errors.num_unmatched, 1u);
    // Third relation: E = T_rel^-1 T_est, T_rel = [Rz(0.1), (1,0,0)], T_est = [I, (1,0,0)]:
    // t_E = R^T (1,0,0) - R^T (1,0,0) = 0, angle 0.1 rad. Errors: translation {0, 0.1, 0}, rotation {0, 0, 0.1 rad}.
    EXPECT_NEAR(errors.translation.mean, 0.1 / 3.0, 1e-9);
    EXPECT_NEAR(errors.translation.max, 0.1, 1e-9);
    EXPECT_NEAR(errors.rotation_deg.mean, 0.1 * 180.0 / kPi / 3.0, 1e-9);
    const double mean = 0.1 * 180.0 / kPi / 3.0;
    EXPECT_NEAR(errors.rotation_deg.std, std::sqrt((2 * mean * mean + std::pow(3 * mean - mean, 2)) / 3.0), 1e-9);
    EXPECT_NEAR(errors.translation_squared.mean, 0.01 / 3.0, 1e-12);
}

TEST(EvaluateRelations, NeedsTimestamps) {
    Trajectory trajectory;
    trajectory.poses = {Eigen::Isometry3d::Identity()};
    EXPECT_THROW(EvaluateRelations(trajectory, {}), ConfigError);
}

}  // namespace
}  // namespace revisit
