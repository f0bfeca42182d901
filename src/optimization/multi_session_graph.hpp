#pragma once
/// One pose graph for several sessions (issue 20): each session's chain of map nodes with its odometry
/// edges, in-session and cross-session closure edges. The first session is anchored (its first node
/// fixed, its frame is the common frame); another session is placed only through cross-session closures
/// that survive the pairwise consistency check (PCM, per pair of sessions) and the robust graph. A
/// session that no surviving closure ties to the anchor is reported as unconnected, never placed.
#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "core/trajectory.hpp"
#include "optimization/closure_consistency.hpp"
#include "optimization/pose_graph.hpp"

namespace revisit {

/// One session's map nodes in its own odometry frame.
struct SessionChain {
    Poses T_odom_node;           ///< odometry pose of each map origin
    std::vector<double> travel;  ///< [m] travelled distance at each node (same size)
};

/// A verified closure between node `query_node` of `query_session` and node `ref_node` of `ref_session`
/// (the same session for an in-session closure).
struct SessionClosure {
    int query_session = 0;
    int query_node = 0;
    int ref_session = 0;
    int ref_node = 0;
    Eigen::Isometry3d T_query_ref = Eigen::Isometry3d::Identity();  ///< the reference node's pose in the query node
    Matrix6d information = Matrix6d::Identity();
    double score = 0.0;  ///< ties between consistent sets (e.g. RANSAC inliers)
    bool is_cross() const { return query_session != ref_session; }
};

struct MultiSessionConfig {
    PoseGraphConfig graph;
    OdometryNoise noise;
    ClosureConsistencyConfig consistency;
    /// A pair of sessions is joined only with at least this many mutually consistent cross closures.
    /// 1 trusts a lone closure that nothing can check (the refinement's overlap test still applies).
    int min_cross_closures = 1;
    double min_weight = 0.1;  ///< closures whose final robust weight falls below this are rejected
};

struct MultiSessionResult {
    int anchor_session = 0;
    std::vector<char> connected;          ///< per session: tied to the anchor by accepted cross closures
    std::vector<Poses> T_common_node;     ///< per session: optimized nodes in the common frame; empty when unconnected
    std::vector<char> closure_accepted;   ///< per input closure
    std::vector<std::string> closure_reason;  ///< per input closure: why rejected; empty when accepted
    std::vector<double> closure_weight;   ///< per input closure: final robust weight (0 when not in the graph)
    int iterations = 0;                   ///< Ceres iterations of the final solve
};

/// Optimizes the sessions jointly; session 0 is the anchor. Throws std::out_of_range for a closure
/// naming a session or node that does not exist, std::invalid_argument for a chain whose travel does
/// not match its nodes.
MultiSessionResult OptimizeSessions(const std::vector<SessionChain>& sessions, const std::vector<SessionClosure>& closures,
                                    const MultiSessionConfig& config);

}  // namespace revisit
