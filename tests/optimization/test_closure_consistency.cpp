#include <gtest/gtest.h>

#include <cmath>

#include "core/se3.hpp"
#include "optimization/closure_consistency.hpp"

namespace revisit {
namespace {

/// Two laps of a 400 m square drive, one node every 10 m (40 per lap), and an odometry that drifts
/// as a real one does, differently on each lap (0.5% long then 0.3% short, 1e-4 rad of heading per
/// metre left then 0.5e-4 right): inside the graph's odometry noise, and it does not cancel around a cycle.
struct TwoLaps {
    Poses truth, odometry;
    std::vector<double> travel;

    TwoLaps() {
        Eigen::Isometry3d odom = Eigen::Isometry3d::Identity();
        for (int k = 0; k < 80; ++k) {
            const int side = (k % 40) / 10, step = k % 10;
            const double yaw = side * M_PI / 2;
            const Eigen::Vector2d corner[] = {{0, 0}, {100, 0}, {100, 100}, {0, 100}};
            const Eigen::Vector2d p = corner[side] + 10.0 * step * Eigen::Vector2d(std::cos(yaw), std::sin(yaw));
            truth.push_back(PoseFromXYZRPY(p.x(), p.y(), 0.0, 0.0, 0.0, yaw));
            if (k > 0) {
                Eigen::Isometry3d delta = truth[k - 1].inverse() * truth[k];
                const bool first_lap = k < 40;
                delta.translation() *= first_lap ? 1.005 : 0.997;
                delta = delta * PoseFromXYZRPY(0, 0, 0, 0, 0, first_lap ? 1e-3 : -0.5e-3);
                odom = odom * delta;
            }
            odometry.push_back(odom);
            travel.push_back(10.0 * k);
        }
    }
    ConsistencyOdometry Odometry() const { return {&odometry, &travel}; }
    /// A true closure from node q (lap two) to node r (lap one), measured within a few centimetres.
    ConsistencyClosure True(int q, int r) const {
        return {q, r, PoseFromXYZRPY(0.03, -0.02, 0, 0, 0, 0.002) * truth[q].inverse() * truth[r], 50.0};
    }
};

const Eigen::Isometry3d kWrong = PoseFromXYZRPY(6.0, -3.0, 0.0, 0.0, 0.0, 0.2);  // a repetitive facade, 6 m off

std::vector<char> Evaluate(const TwoLaps& laps, const std::vector<ConsistencyClosure>& closures) {
    ClosureConsistency consistency(ClosureConsistencyConfig{}, OdometryNoise{});
    for (const auto& c : closures) consistency.Add(c, laps.Odometry());
    return consistency.ConsistentSet();
}

TEST(ClosureConsistency, TrueClosuresAreConsistentAndAllKept) {
    const TwoLaps laps;
    std::vector<ConsistencyClosure> closures;
    for (int r : {2, 9, 17, 25, 33, 38}) closures.push_back(laps.True(40 + r, r));
    // The 40 m shifted closure (node 45 -> node 1, as seen from 4 nodes later) also holds.
    closures.push_back(laps.True(45, 1));
    const auto keep = Evaluate(laps, closures);
    for (std::size_t k = 0; k < keep.size(); ++k) EXPECT_TRUE(keep[k]) << "closure " << k;
    EXPECT_LT(CycleChi2(closures[0], closures[5], laps.Odometry(), OdometryNoise{}, ClosureConsistencyConfig{}), 16.81);
}

TEST(ClosureConsistency, OneWrongClosureAmongConsistentOnesIsDropped) {
    const TwoLaps laps;
    std::vector<ConsistencyClosure> closures;
    for (int r : {3, 12, 21, 30}) closures.push_back(laps.True(40 + r, r));
    auto wrong = laps.True(55, 15);
    wrong.T_query_ref = wrong.T_query_ref * kWrong;
    wrong.score = 500.0;  // more inliers than any true one: the inlier count alone cannot reject it
    closures.insert(closures.begin() + 2, wrong);
    const auto keep = Evaluate(laps, closures);
    EXPECT_EQ(keep, (std::vector<char>{1, 1, 0, 1, 1}));
}

TEST(ClosureConsistency, TwoMutuallyConsistentWrongClosuresAgainstManyRightOnesAreDropped) {
    const TwoLaps laps;
    std::vector<ConsistencyClosure> closures;
    for (int r : {1, 6, 11, 19, 27, 34}) closures.push_back(laps.True(40 + r, r));
    // Two queries confuse the same place with another: they agree with each other (same reference,
    // same error), not with the drive.
    for (int q : {62, 63}) {
        auto wrong = laps.True(q, 22);
        wrong.T_query_ref = wrong.T_query_ref * kWrong;
        closures.push_back(wrong);
    }
    ClosureConsistency consistency(ClosureConsistencyConfig{}, OdometryNoise{});
    for (const auto& c : closures) consistency.Add(c, laps.Odometry());
    EXPECT_TRUE(consistency.Consistent(6, 7));
    EXPECT_FALSE(consistency.Consistent(3, 6));  // the true closure 59 -> 19, 30 m of travel away
    EXPECT_EQ(consistency.ConsistentSet(), (std::vector<char>{1, 1, 1, 1, 1, 1, 0, 0}));
}

TEST(ClosureConsistency, ClosuresTheOdometryContradictsAreDroppedEvenWhenTheyAgreeWithEachOther) {
    // A corridor of identical rooms seen from its other end: two queries match the same place turned by
    // 180 deg, agree with each other, and have more inliers than the two true closures. A cycle cannot
    // tell the pairs apart (2 against 2); the odometry can: over 260 m of travel it turns by
    // 3e-4 rad/m x 260 m = 4.5 deg (1 sigma), not 180.
    const TwoLaps laps;
    const Eigen::Isometry3d turned = PoseFromXYZRPY(4.0, 0.0, 0.0, 0.0, 0.0, M_PI);
    std::vector<ConsistencyClosure> closures = {laps.True(47, 7), laps.True(52, 12)};
    for (int q : {66, 67}) {
        auto wrong = laps.True(q, 26);
        wrong.T_query_ref = wrong.T_query_ref * turned;
        wrong.score = 200.0;
        closures.push_back(wrong);
    }
    ClosureConsistency consistency(ClosureConsistencyConfig{}, OdometryNoise{});
    for (const auto& c : closures) consistency.Add(c, laps.Odometry());
    EXPECT_EQ(consistency.ConsistentSet(), (std::vector<char>{1, 1, 0, 0}));
    EXPECT_FALSE(consistency.ContradictsOdometry(0));
    EXPECT_FALSE(consistency.ContradictsOdometry(1));
    EXPECT_TRUE(consistency.ContradictsOdometry(2));
    EXPECT_TRUE(consistency.ContradictsOdometry(3));
    EXPECT_GT(consistency.OdometryChi2Of(2), 100.0);
    EXPECT_LT(CycleChi2(closures[2], closures[3], laps.Odometry(), OdometryNoise{}, ClosureConsistencyConfig{}), 16.81);
}

TEST(ClosureConsistency, AShiftTheHeadingDriftWouldHaveTurnedIsInconsistent) {
    // Two closures from one query to two places 80 m apart on a straight side. The second is shifted
    // 18 m sideways (two rooms of a repetitive corridor) with its rotation right. Under a 2D laser's
    // loose heading sigma (2e-3 rad/m: 9 deg over the leg) an even drift that moved the leg's end 18 m
    // sideways would have turned it by 18 m / 40 m = 26 deg, and the cycle closes in rotation; what a
    // wandering drift adds is 3.7 m (1 sigma). Taken as independent of the rotation (sigma_r x 40 m =
    // 6.4 m of sideways swing) the shift would pass.
    const TwoLaps laps;
    OdometryNoise loose;
    loose.rotation_per_m = 2e-3;
    const auto a = laps.True(41, 1);
    auto shifted = laps.True(41, 9);
    shifted.T_query_ref = shifted.T_query_ref * PoseFromXYZRPY(0.0, 18.0, 0.0, 0.0, 0.0, 0.0);
    EXPECT_GT(CycleChi2(a, shifted, laps.Odometry(), loose, ClosureConsistencyConfig{}), 16.81);
    EXPECT_LT(CycleChi2(a, laps.True(41, 9), laps.Odometry(), loose, ClosureConsistencyConfig{}), 1.0);
    // The means of the legs from the nodes' positions give the same verdicts.
    std::vector<Eigen::Vector3d> integral;
    AppendPositionIntegral(laps.odometry, laps.travel, integral);
    ConsistencyOdometry with_means = laps.Odometry();
    with_means.position_integral = &integral;
    EXPECT_GT(CycleChi2(a, shifted, with_means, loose, ClosureConsistencyConfig{}), 16.81);
    EXPECT_LT(CycleChi2(a, laps.True(41, 9), with_means, loose, ClosureConsistencyConfig{}), 1.0);
}

TEST(ClosureConsistency, TheDriftTheClosuresShowTightensALooseRateAndDropsAShiftedTwin) {
    // indoor-2d-180's false closure: a room matched one room along (9 m, rotation right). Under a 2D
    // laser's prior heading rate (2e-3 rad/m) a drift could have put it there, so it agrees with the
    // true closures; the true closures themselves show a drift near 1e-4 rad/m (TwoLaps), and under
    // three times that the twin agrees with none of them.
    const TwoLaps laps;
    OdometryNoise loose;
    loose.rotation_per_m = 2e-3;
    std::vector<ConsistencyClosure> closures;
    for (int r : {2, 9, 25, 33}) closures.push_back(laps.True(40 + r, r));
    auto twin = laps.True(57, 17);  // 80 m of travel from the nearest true closure
    twin.T_query_ref = twin.T_query_ref * PoseFromXYZRPY(9.0, 0.0, 0.0, 0.0, 0.0, 0.0);
    twin.score = 500.0;
    closures.insert(closures.begin() + 2, twin);
    ClosureConsistency consistency(ClosureConsistencyConfig{}, loose);
    for (const auto& c : closures) consistency.Add(c, laps.Odometry());
    EXPECT_EQ(consistency.ConsistentSet(), (std::vector<char>{1, 1, 1, 1, 1}));

    EXPECT_FALSE(consistency.ObservedRotationRate(laps.Odometry(), 6).has_value());  // too few to trust
    const auto observed = consistency.ObservedRotationRate(laps.Odometry(), 3);
    ASSERT_TRUE(observed.has_value());
    EXPECT_GT(*observed, 1e-5);
    EXPECT_LT(*observed, 2e-4);
    OdometryNoise calibrated = loose;
    calibrated.rotation_per_m = 3.0 * *observed;
    const ClosureConsistency rechecked = consistency.Rechecked(calibrated, laps.Odometry());
    EXPECT_EQ(rechecked.ConsistentSet(), (std::vector<char>{1, 1, 0, 1, 1}));
    EXPECT_DOUBLE_EQ(rechecked.noise().rotation_per_m, calibrated.rotation_per_m);
}

TEST(ClosureConsistency, ASingleClosureIsKeptAndDisablingKeepsAll) {
    const TwoLaps laps;
    auto wrong = laps.True(50, 10);
    wrong.T_query_ref = wrong.T_query_ref * kWrong;
    EXPECT_EQ(Evaluate(laps, {wrong}), std::vector<char>{1});

    ClosureConsistencyConfig off;
    off.enabled = false;
    ClosureConsistency consistency(off, OdometryNoise{});
    consistency.Add(laps.True(50, 10), laps.Odometry());
    consistency.Add(wrong, laps.Odometry());
    EXPECT_EQ(consistency.ConsistentSet(), (std::vector<char>{1, 1}));
}

TEST(ClosureConsistency, AClosureThatMayNotDisplaceJoinsOnlyASetItAgreesWith) {
    // The proximity pass's closures come after the detector's: two wrong ones that agree with each other
    // would outnumber the one true closure and displace it; they may not.
    const TwoLaps laps;
    ClosureConsistency consistency(ClosureConsistencyConfig{}, OdometryNoise{});
    consistency.Add(laps.True(59, 19), laps.Odometry());
    for (int q : {62, 63}) {
        auto wrong = laps.True(q, 22);
        wrong.T_query_ref = wrong.T_query_ref * kWrong;
        consistency.Add(wrong, laps.Odometry(), false);
    }
    EXPECT_TRUE(consistency.Consistent(1, 2));
    EXPECT_EQ(consistency.ConsistentSet(), (std::vector<char>{1, 0, 0}));
    consistency.Add(laps.True(70, 30), laps.Odometry(), false);  // agrees with the set: joins it
    EXPECT_EQ(consistency.ConsistentSet(), (std::vector<char>{1, 0, 0, 1}));

    // Allowed to displace, the same two wrong closures take the set from the lone true one.
    ClosureConsistency displacing(ClosureConsistencyConfig{}, OdometryNoise{});
    displacing.Add(laps.True(59, 19), laps.Odometry());
    for (int q : {62, 63}) {
        auto wrong = laps.True(q, 22);
        wrong.T_query_ref = wrong.T_query_ref * kWrong;
        displacing.Add(wrong, laps.Odometry());
    }
    EXPECT_EQ(displacing.ConsistentSet(), (std::vector<char>{0, 1, 1}));
}

TEST(MaximumClique, ExactOnSmallGraphsTiesByWeightAndDeterministic) {
    // Two triangles {0,1,2} and {3,4,5} joined by edge 2-3; the second is heavier.
    std::vector<std::vector<char>> adjacency(6, std::vector<char>(6, 0));
    auto link = [&](int a, int b) { adjacency[a][b] = adjacency[b][a] = 1; };
    link(0, 1), link(1, 2), link(0, 2), link(3, 4), link(4, 5), link(3, 5), link(2, 3);
    EXPECT_EQ(MaximumClique(adjacency, {1, 1, 1, 2, 2, 2}, 1000), (std::vector<std::size_t>{3, 4, 5}));
    EXPECT_EQ(MaximumClique(adjacency, {2, 2, 2, 1, 1, 1}, 1000), (std::vector<std::size_t>{0, 1, 2}));
    // A 4-clique hidden behind a high-degree vertex that the greedy start picks first.
    link(0, 4), link(1, 4), link(2, 4);
    EXPECT_EQ(MaximumClique(adjacency, std::vector<double>(6, 1.0), 1000), (std::vector<std::size_t>{0, 1, 2, 4}));
}

}  // namespace
}  // namespace revisit
