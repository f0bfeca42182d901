#include <gtest/gtest.h>

#include <cmath>

#include "core/se3.hpp"
#include "optimization/multi_session_graph.hpp"

namespace revisit {
namespace {

/// A 100 m square block, one node every 10 m (40 per lap). Session A drives one lap from the south-west
/// corner with exact odometry (its frame is the world frame). Session B starts elsewhere on the block
/// (`start` nodes further), drives one lap with drifting odometry (0.5% long, 1e-3 rad of heading per
/// node), and its odometry frame is its own first pose: only cross closures can place it.
Eigen::Isometry3d BlockPose(int index) {
    const int k = index % 40, side = k / 10, step = k % 10;
    const double yaw = side * M_PI / 2;
    const Eigen::Vector2d corner[] = {{0, 0}, {100, 0}, {100, 100}, {0, 100}};
    const Eigen::Vector2d p = corner[side] + 10.0 * step * Eigen::Vector2d(std::cos(yaw), std::sin(yaw));
    return PoseFromXYZRPY(p.x(), p.y(), 0.0, 0.0, 0.0, yaw);
}

struct Session {
    Poses truth;
    SessionChain chain;
};

Session DriveBlock(int start, double scale_error, double yaw_per_node) {
    Session session;
    Eigen::Isometry3d odom = Eigen::Isometry3d::Identity();
    for (int k = 0; k < 40; ++k) {
        session.truth.push_back(BlockPose(start + k));
        if (k > 0) {
            Eigen::Isometry3d delta = session.truth[k - 1].inverse() * session.truth[k];
            delta.translation() *= 1.0 + scale_error;
            odom = odom * delta * PoseFromXYZRPY(0, 0, 0, 0, 0, yaw_per_node);
        }
        session.chain.T_odom_node.push_back(odom);
        session.chain.travel.push_back(10.0 * k);
    }
    return session;
}

const Matrix6d kClosureInformation = DiagonalInformation(0.05, 0.005);

/// A true closure from node q of session qs to node r of session rs, measured within a few centimetres.
SessionClosure TrueClosure(const std::vector<Session>& sessions, int qs, int q, int rs, int r) {
    const Eigen::Isometry3d measured =
        PoseFromXYZRPY(0.03, -0.02, 0, 0, 0, 0.002) * sessions[qs].truth[q].inverse() * sessions[rs].truth[r];
    return {qs, q, rs, r, measured, kClosureInformation, 50.0};
}

std::vector<SessionChain> Chains(const std::vector<Session>& sessions) {
    std::vector<SessionChain> chains;
    for (const auto& s : sessions) chains.push_back(s.chain);
    return chains;
}

/// Largest position error [m] of a session's optimized nodes against its truth (no alignment: the
/// common frame is session A's, which is the world frame here).
double MaxError(const Poses& estimate, const Poses& truth) {
    double worst = 0.0;
    for (std::size_t i = 0; i < truth.size(); ++i) worst = std::max(worst, (estimate[i].translation() - truth[i].translation()).norm());
    return worst;
}

// B's node j is at block index 15 + j, where A's node (15 + j) % 40 is.
int ANodeAt(int b_node) { return (15 + b_node) % 40; }

TEST(MultiSessionGraph, OneCrossClosurePlacesTheSecondSession) {
    const std::vector<Session> sessions = {DriveBlock(0, 0.0, 0.0), DriveBlock(15, 0.005, 1e-3)};
    const std::vector<SessionClosure> closures = {TrueClosure(sessions, 1, 10, 0, ANodeAt(10))};
    const auto result = OptimizeSessions(Chains(sessions), closures, MultiSessionConfig{});
    ASSERT_EQ(result.connected, (std::vector<char>{1, 1}));
    ASSERT_EQ(result.T_common_node[1].size(), 40u);
    EXPECT_TRUE(result.closure_accepted[0]);
    // Near the closure, B sits where it truly is; A (exact odometry, anchored) does not move.
    EXPECT_LT((result.T_common_node[1][10].translation() - sessions[1].truth[10].translation()).norm(), 0.2);
    EXPECT_LT(MaxError(result.T_common_node[0], sessions[0].truth), 1e-6);
}

TEST(MultiSessionGraph, SeveralCrossClosuresCorrectTheSecondSessionsDrift) {
    const std::vector<Session> sessions = {DriveBlock(0, 0.0, 0.0), DriveBlock(15, 0.005, 1e-3)};
    std::vector<SessionClosure> closures;
    for (int j : {2, 12, 22, 32, 38}) closures.push_back(TrueClosure(sessions, 1, j, 0, ANodeAt(j)));
    const auto one = OptimizeSessions(Chains(sessions), {closures[0]}, MultiSessionConfig{});
    const auto all = OptimizeSessions(Chains(sessions), closures, MultiSessionConfig{});
    ASSERT_TRUE(all.connected[1]);
    for (std::size_t k = 0; k < closures.size(); ++k) EXPECT_TRUE(all.closure_accepted[k]) << all.closure_reason[k];
    // One closure leaves B's drift (~3 m at the far end of the lap); five bring it under a metre (the closures share a 2 mrad bias).
    EXPECT_GT(MaxError(one.T_common_node[1], sessions[1].truth), 2.0) << MaxError(all.T_common_node[1], sessions[1].truth);
    EXPECT_LT(MaxError(all.T_common_node[1], sessions[1].truth), 1.0);
}

TEST(MultiSessionGraph, AFalseCrossClosureIsRejected) {
    const std::vector<Session> sessions = {DriveBlock(0, 0.0, 0.0), DriveBlock(15, 0.005, 1e-3)};
    std::vector<SessionClosure> closures;
    for (int j : {2, 12, 22, 32}) closures.push_back(TrueClosure(sessions, 1, j, 0, ANodeAt(j)));
    // A repetitive facade: B's node 20 matched to the right place 6 m and 11 degrees off, with more
    // inliers than any true closure; and the closure stated from A's side (query in the anchor).
    auto wrong = TrueClosure(sessions, 0, ANodeAt(20), 1, 20);
    wrong.T_query_ref = wrong.T_query_ref * PoseFromXYZRPY(6.0, -3.0, 0.0, 0.0, 0.0, 0.2);
    wrong.score = 500.0;
    closures.insert(closures.begin() + 2, wrong);
    const auto result = OptimizeSessions(Chains(sessions), closures, MultiSessionConfig{});
    EXPECT_EQ(result.closure_accepted, (std::vector<char>{1, 1, 0, 1, 1}));
    EXPECT_NE(result.closure_reason[2].find("PCM"), std::string::npos) << result.closure_reason[2];
    EXPECT_LT(MaxError(result.T_common_node[1], sessions[1].truth), 1.0);
}

TEST(MultiSessionGraph, ASessionWithoutCrossClosuresIsUnconnectedNotPlaced) {
    const std::vector<Session> sessions = {DriveBlock(0, 0.0, 0.0), DriveBlock(15, 0.005, 1e-3), DriveBlock(25, 0.0, 0.0)};
    // B and C close with each other but never with A: neither is in A's frame.
    const std::vector<SessionClosure> closures = {TrueClosure(sessions, 2, 5, 1, 15), TrueClosure(sessions, 2, 20, 1, 30)};
    const auto result = OptimizeSessions(Chains(sessions), closures, MultiSessionConfig{});
    EXPECT_EQ(result.connected, (std::vector<char>{1, 0, 0}));
    EXPECT_TRUE(result.T_common_node[1].empty());
    EXPECT_TRUE(result.T_common_node[2].empty());
    EXPECT_FALSE(result.closure_accepted[0]);
    EXPECT_EQ(result.closure_reason[0], "between sessions not tied to the anchor");
}

TEST(MultiSessionGraph, ASessionJoinsThroughAnotherAndLoneClosuresCanBeRefused) {
    const std::vector<Session> sessions = {DriveBlock(0, 0.0, 0.0), DriveBlock(15, 0.0, 0.0), DriveBlock(25, 0.0, 0.0)};
    std::vector<SessionClosure> closures = {TrueClosure(sessions, 1, 5, 0, ANodeAt(5)), TrueClosure(sessions, 2, 5, 1, 15)};
    const auto chained = OptimizeSessions(Chains(sessions), closures, MultiSessionConfig{});
    EXPECT_EQ(chained.connected, (std::vector<char>{1, 1, 1}));
    EXPECT_LT(MaxError(chained.T_common_node[2], sessions[2].truth), 0.6);  // two closures, 2 mrad each, 140 m lever

    MultiSessionConfig cautious;
    cautious.min_cross_closures = 2;
    closures.push_back(TrueClosure(sessions, 1, 25, 0, ANodeAt(25)));
    const auto result = OptimizeSessions(Chains(sessions), closures, cautious);
    EXPECT_EQ(result.connected, (std::vector<char>{1, 1, 0}));
    EXPECT_NE(result.closure_reason[1].find("too few"), std::string::npos) << result.closure_reason[1];
}

TEST(MultiSessionGraph, RejectsClosuresNamingMissingNodes) {
    const std::vector<Session> sessions = {DriveBlock(0, 0.0, 0.0)};
    EXPECT_THROW(OptimizeSessions(Chains(sessions), {{0, 1, 1, 0, {}, kClosureInformation, 1.0}}, {}), std::out_of_range);
    EXPECT_THROW(OptimizeSessions(Chains(sessions), {{0, 3, 0, 40, {}, kClosureInformation, 1.0}}, {}), std::out_of_range);
}

}  // namespace
}  // namespace revisit
