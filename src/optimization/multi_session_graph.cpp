#include "optimization/multi_session_graph.hpp"

#include <algorithm>
#include <cstdio>
#include <map>
#include <numeric>
#include <optional>
#include <stdexcept>
#include <utility>

namespace revisit {
namespace {

void Validate(const std::vector<SessionChain>& sessions, const std::vector<SessionClosure>& closures) {
    for (std::size_t s = 0; s < sessions.size(); ++s) {
        if (sessions[s].travel.size() != sessions[s].T_odom_node.size()) {
            throw std::invalid_argument("session " + std::to_string(s) + " has " + std::to_string(sessions[s].travel.size()) +
                                        " travel values for " + std::to_string(sessions[s].T_odom_node.size()) + " nodes");
        }
    }
    const auto valid = [&](int session, int node) {
        return session >= 0 && session < int(sessions.size()) && node >= 0 &&
               node < int(sessions[std::size_t(session)].T_odom_node.size());
    };
    for (std::size_t k = 0; k < closures.size(); ++k) {
        const auto& c = closures[k];
        if (!valid(c.query_session, c.query_node) || !valid(c.ref_session, c.ref_node) ||
            (!c.is_cross() && c.query_node == c.ref_node)) {
            throw std::out_of_range("closure " + std::to_string(k) + " joins session " + std::to_string(c.query_session) +
                                    " node " + std::to_string(c.query_node) + " and session " +
                                    std::to_string(c.ref_session) + " node " + std::to_string(c.ref_node));
        }
    }
}

/// PCM within each pair of sessions: cycles are only defined between closures joining the same two
/// sessions (both odometry legs then stay inside one session each). Cross closures are turned so the
/// query lies in the later session and nodes are numbered [earlier session's, later session's].
void CheckConsistency(const std::vector<SessionChain>& sessions, const std::vector<SessionClosure>& closures,
                      const MultiSessionConfig& config, MultiSessionResult& result) {
    std::map<std::pair<int, int>, std::vector<std::size_t>> groups;
    for (std::size_t k = 0; k < closures.size(); ++k) {
        const auto& c = closures[k];
        groups[{std::min(c.query_session, c.ref_session), std::max(c.query_session, c.ref_session)}].push_back(k);
    }
    for (const auto& [pair, members] : groups) {
        const auto& [a, b] = pair;
        Poses nodes = sessions[std::size_t(a)].T_odom_node;
        std::vector<double> travel = sessions[std::size_t(a)].travel;
        const int offset = a == b ? 0 : int(nodes.size());
        if (a != b) {
            nodes.insert(nodes.end(), sessions[std::size_t(b)].T_odom_node.begin(), sessions[std::size_t(b)].T_odom_node.end());
            travel.insert(travel.end(), sessions[std::size_t(b)].travel.begin(), sessions[std::size_t(b)].travel.end());
        }
        ClosureConsistency consistency(config.consistency, config.noise);
        for (const std::size_t k : members) {
            const auto& c = closures[k];
            ConsistencyClosure turned{c.query_node + offset, c.ref_node, c.T_query_ref, c.score};
            if (a != b && c.query_session == a) turned = {c.ref_node + offset, c.query_node, c.T_query_ref.inverse(), c.score};
            consistency.Add(turned, {&nodes, &travel, nullptr, a == b});
        }
        const auto keep = consistency.ConsistentSet();
        int kept = 0;
        for (std::size_t i = 0; i < members.size(); ++i) kept += keep[i] != 0;
        for (std::size_t i = 0; i < members.size(); ++i) {
            const std::size_t k = members[i];
            if (!keep[i]) {
                result.closure_reason[k] = "inconsistent with other closures (PCM)";
            } else if (a != b && kept < config.min_cross_closures) {
                result.closure_reason[k] = "too few consistent closures between sessions " + std::to_string(a) + " and " +
                                           std::to_string(b) + " (" + std::to_string(kept) + " < " +
                                           std::to_string(config.min_cross_closures) + ")";
            } else {
                result.closure_accepted[k] = 1;
            }
        }
    }
}

/// Places every session reachable from the anchor through accepted cross closures (the strongest
/// closure first), breadth first in session order: T_common_odom per session, empty when unreachable.
std::vector<std::optional<Eigen::Isometry3d>> PlaceSessions(const std::vector<SessionChain>& sessions,
                                                            const std::vector<SessionClosure>& closures,
                                                            const std::vector<char>& accepted) {
    std::vector<std::size_t> order(closures.size());
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(), [&](std::size_t x, std::size_t y) { return closures[x].score > closures[y].score; });
    std::vector<std::optional<Eigen::Isometry3d>> T_common_odom(sessions.size());
    if (sessions.empty()) return T_common_odom;
    T_common_odom[0] = Eigen::Isometry3d::Identity();
    for (bool placed_one = true; placed_one;) {
        placed_one = false;
        for (const std::size_t k : order) {
            const auto& c = closures[k];
            if (!accepted[k] || !c.is_cross()) continue;
            const auto& query_frame = T_common_odom[std::size_t(c.query_session)];
            const auto& ref_frame = T_common_odom[std::size_t(c.ref_session)];
            if (query_frame.has_value() == ref_frame.has_value()) continue;
            const Eigen::Isometry3d& T_odom_query = sessions[std::size_t(c.query_session)].T_odom_node[std::size_t(c.query_node)];
            const Eigen::Isometry3d& T_odom_ref = sessions[std::size_t(c.ref_session)].T_odom_node[std::size_t(c.ref_node)];
            if (ref_frame) {
                const Eigen::Isometry3d T_common_query = *ref_frame * T_odom_ref * c.T_query_ref.inverse();
                T_common_odom[std::size_t(c.query_session)] = T_common_query * T_odom_query.inverse();
            } else {
                const Eigen::Isometry3d T_common_ref = *query_frame * T_odom_query * c.T_query_ref;
                T_common_odom[std::size_t(c.ref_session)] = T_common_ref * T_odom_ref.inverse();
            }
            placed_one = true;
            break;  // restart from the strongest closure: placement follows the best links first
        }
    }
    return T_common_odom;
}

std::string FormatWeight(double weight) {
    char text[32];
    std::snprintf(text, sizeof(text), "%.2g", weight);
    return text;
}

}  // namespace

MultiSessionResult OptimizeSessions(const std::vector<SessionChain>& sessions, const std::vector<SessionClosure>& closures,
                                    const MultiSessionConfig& config) {
    Validate(sessions, closures);
    MultiSessionResult result;
    result.connected.assign(sessions.size(), 0);
    result.T_common_node.assign(sessions.size(), {});
    result.closure_accepted.assign(closures.size(), 0);
    result.closure_reason.assign(closures.size(), "");
    result.closure_weight.assign(closures.size(), 0.0);
    if (sessions.empty()) return result;
    CheckConsistency(sessions, closures, config, result);

    // Rejecting a cross closure in the graph can cut a session loose: solve again until no cross
    // closure is rejected (each round removes at least one, so this ends).
    for (;;) {
        const auto T_common_odom = PlaceSessions(sessions, closures, result.closure_accepted);
        std::vector<int> offset(sessions.size(), -1);
        Poses initial;
        std::vector<PoseGraphEdge> edges;
        for (std::size_t s = 0; s < sessions.size(); ++s) {
            if (!T_common_odom[s]) continue;
            offset[s] = int(initial.size());
            const auto& chain = sessions[s];
            for (std::size_t i = 0; i < chain.T_odom_node.size(); ++i) {
                initial.push_back(*T_common_odom[s] * chain.T_odom_node[i]);
                if (i == 0) continue;
                edges.push_back({offset[s] + int(i) - 1, offset[s] + int(i), chain.T_odom_node[i - 1].inverse() * chain.T_odom_node[i],
                                 OdometryInformation(chain.travel[i] - chain.travel[i - 1], config.noise), false});
            }
        }
        std::vector<std::size_t> loop_closure;
        for (std::size_t k = 0; k < closures.size(); ++k) {
            const auto& c = closures[k];
            if (!result.closure_accepted[k] || offset[std::size_t(c.query_session)] < 0 || offset[std::size_t(c.ref_session)] < 0) continue;
            edges.push_back({offset[std::size_t(c.query_session)] + c.query_node, offset[std::size_t(c.ref_session)] + c.ref_node,
                             c.T_query_ref, c.information, true});
            loop_closure.push_back(k);
        }
        const std::size_t num_odometry = edges.size() - loop_closure.size();
        const PoseGraphResult solved = OptimizePoseGraph(initial, edges, config.graph);
        result.iterations = solved.iterations;
        bool cut_cross = false;
        for (std::size_t i = 0; i < loop_closure.size(); ++i) {
            const std::size_t k = loop_closure[i];
            result.closure_weight[k] = solved.edge_weights[num_odometry + i];
            if (result.closure_weight[k] >= config.min_weight) continue;
            result.closure_accepted[k] = 0;
            result.closure_reason[k] = "inconsistent with the pose graph (weight " + FormatWeight(result.closure_weight[k]) +
                                       " < " + FormatWeight(config.min_weight) + ")";
            cut_cross = cut_cross || closures[k].is_cross();
        }
        if (cut_cross) continue;
        for (std::size_t s = 0; s < sessions.size(); ++s) {
            result.connected[s] = offset[s] >= 0;
            if (offset[s] < 0) continue;
            const auto first = solved.T_world_node.begin() + offset[s];
            result.T_common_node[s].assign(first, first + std::ptrdiff_t(sessions[s].T_odom_node.size()));
        }
        // Closures touching an unconnected session are not in the graph: say so.
        for (std::size_t k = 0; k < closures.size(); ++k) {
            const auto& c = closures[k];
            if (result.closure_accepted[k] && !(result.connected[std::size_t(c.query_session)] && result.connected[std::size_t(c.ref_session)])) {
                result.closure_weight[k] = 0.0;
                if (c.is_cross()) {
                    result.closure_accepted[k] = 0;
                    result.closure_reason[k] = "between sessions not tied to the anchor";
                }
            }
        }
        return result;
    }
}

}  // namespace revisit
