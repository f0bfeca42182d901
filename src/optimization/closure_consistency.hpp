#pragma once
/// Pairwise consistency of loop closures (PCM, Mangelson et al. 2018): two closures agree when the
/// cycle they close with the odometry is near identity; the largest set of mutually agreeing closures
/// is kept before the pose graph, so that wrong closures that agree with nothing cannot bend it.
#include <Eigen/Geometry>
#include <cstddef>
#include <vector>

#include "core/trajectory.hpp"
#include "optimization/pose_graph.hpp"

namespace revisit {

struct ClosureConsistencyConfig {
    bool enabled = true;                      ///< check closures pairwise before the pose graph
    double chi2_threshold = 16.81;            ///< cycle chi^2 bound: 99% quantile of chi^2 with 6 degrees of freedom
    double closure_sigma_translation = 0.5;   ///< [m] error of one verified closure (what counts as a true one)
    double closure_sigma_rotation_deg = 2.0;  ///< [deg]
    int exact_max_steps = 20000;              ///< branch-and-bound budget; past it the best set found so far is kept
};

/// A verified closure between two pose-graph nodes: T_query_ref is the reference node's pose in the query node.
struct ConsistencyClosure {
    int query_node = 0;
    int ref_node = 0;
    Eigen::Isometry3d T_query_ref = Eigen::Isometry3d::Identity();
    double score = 0.0;  ///< breaks ties between sets of equal size (e.g. RANSAC inliers)
};

/// The odometry the cycles go through: node poses (odometry, never optimized) and the travelled
/// distance [m] at each node.
struct ConsistencyOdometry {
    const Poses* T_world_node = nullptr;
    const std::vector<double>* travel = nullptr;
};

/// chi^2 of the cycle T_qa_ra * odom(ra -> rb) * T_qb_rb^-1 * odom(qb -> qa). Odometry sigma grows
/// linearly with the travel along each of the two odometry legs (as the pose graph's odometry edges),
/// plus the position error the leg's heading drift causes (rotation sigma x travel / 2); each closure
/// adds the config's closure sigma. Translation and rotation errors are taken as isotropic.
double CycleChi2(const ConsistencyClosure& a, const ConsistencyClosure& b, const ConsistencyOdometry& odometry,
                 const OdometryNoise& noise, const ClosureConsistencyConfig& config);

/// The largest clique of an undirected graph (adjacency[i][j] != 0: i and j agree), ties broken by
/// the larger sum of `weight`. Exact branch and bound, started from a greedy clique and bounded by
/// `max_steps` expansions (deterministic: the same input gives the same set). Sorted indices.
std::vector<std::size_t> MaximumClique(const std::vector<std::vector<char>>& adjacency, const std::vector<double>& weight,
                                       int max_steps);

/// Grows with the closures as they are verified; each Add computes one row of the pairwise table.
class ClosureConsistency {
  public:
    ClosureConsistency(const ClosureConsistencyConfig& config, const OdometryNoise& noise) : config_(config), noise_(noise) {}

    /// Adds a closure and updates the set; the odometry must hold both of its nodes (and those of every
    /// earlier closure). Cost: one cycle per earlier closure, and a clique search among the new
    /// closure's consistent partners only when it disagrees with the current set.
    void Add(const ConsistencyClosure& closure, const ConsistencyOdometry& odometry);
    /// One flag per added closure: in the maximum consistent set (ties: the larger sum of scores), kept
    /// incrementally as closures arrive. A single closure is kept (nothing to check it against); with
    /// the check disabled every closure is kept.
    std::vector<char> ConsistentSet() const;

    std::size_t size() const { return closures_.size(); }
    bool Consistent(std::size_t a, std::size_t b) const { return consistent_[a][b] != 0; }

  private:
    ClosureConsistencyConfig config_;
    OdometryNoise noise_;
    std::vector<ConsistencyClosure> closures_;
    std::vector<std::vector<char>> consistent_;
    std::vector<char> in_set_;  ///< the maximum consistent set, kept up to date by Add
    std::size_t set_size_ = 0;
    double set_weight_ = 0.0;
};

}  // namespace revisit
