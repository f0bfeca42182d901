#pragma once
/// Pairwise consistency of loop closures (PCM, Mangelson et al. 2018): two closures agree when the
/// cycle they close with the odometry is near identity; the largest set of mutually agreeing closures
/// is kept before the pose graph, so that wrong closures that agree with nothing cannot bend it.
#include <Eigen/Geometry>
#include <cstddef>
#include <optional>
#include <vector>

#include "core/trajectory.hpp"
#include "optimization/pose_graph.hpp"

namespace revisit {

struct ClosureConsistencyConfig {
    bool enabled = true;                      ///< check closures pairwise before the pose graph
    double chi2_threshold = 16.81;            ///< cycle chi^2 bound: 99% quantile of chi^2 with 6 degrees of freedom
    /// A closure checked against the odometry alone is rejected without another closure to confirm the
    /// verdict: held to a 1e-4 false rejection (99.99% quantile, 6 dof) instead of the pairs' 1e-2.
    double odometry_chi2_threshold = 27.86;
    double closure_sigma_translation = 0.5;   ///< [m] error of one verified closure (what counts as a true one)
    double closure_sigma_rotation_deg = 2.0;  ///< [deg]
    int exact_max_steps = 20000;              ///< branch-and-bound budget; past it the best set found so far is kept
    /// Drift calibration (`ClosureConsistency::ObservedRotationRate`): at the end of a run, once the set holds
    /// `calibration_min_closures` closures, `calibration_factor` x the largest rotation drift they show replaces the
    /// configured rate when that is lower (never below `calibration_min_rotation_per_m`), and the set is
    /// checked again. Only ever tighter: a looser bound would admit closures nothing has confirmed.
    bool calibrate_drift = true;
    int calibration_min_closures = 3;
    double calibration_factor = 3.0;
    double calibration_min_rotation_per_m = 3e-4;  ///< [rad/m] the 3D default (graph.odometry_rotation_per_m)
};

/// A verified closure between two pose-graph nodes: T_query_ref is the reference node's pose in the query node.
struct ConsistencyClosure {
    int query_node = 0;
    int ref_node = 0;
    Eigen::Isometry3d T_query_ref = Eigen::Isometry3d::Identity();
    double score = 0.0;  ///< breaks ties between sets of equal size (e.g. RANSAC inliers)
};

/// The odometry the cycles go through: node poses (odometry, never optimized), the travelled
/// distance [m] at each node and, optionally, the integral of the node positions over travel
/// (`AppendPositionIntegral`), which gives each leg's mean position; without it a leg's mean
/// position is taken halfway along its chord.
struct ConsistencyOdometry {
    const Poses* T_world_node = nullptr;
    const std::vector<double>* travel = nullptr;
    const std::vector<Eigen::Vector3d>* position_integral = nullptr;  ///< [m^2] sum of position x travel
    /// The nodes form one odometry chain, so a closure can be checked against the odometry alone; false
    /// for the nodes of two sessions side by side (only cycles with one leg in each are defined).
    bool one_chain = true;
};

/// Extends `integral` to the last node of `T_world_node` (trapezoids between consecutive nodes).
void AppendPositionIntegral(const Poses& T_world_node, const std::vector<double>& travel, std::vector<Eigen::Vector3d>& integral);

/// chi^2 (6 dof) of the cycle T_qa_ra * odom(ra -> rb) * T_qb_rb^-1 * odom(qb -> qa). Along each of
/// the two odometry legs the translation sigma grows linearly with the travel (as the pose graph's
/// odometry edges) and so does the rotation sigma; a rotation drift also moves the leg's end, by the
/// drift angle times the distance from the leg's mean position to its end, and that displacement is
/// tied to the rotation it comes with (the same drift), not independent of it: a cycle whose rotation
/// closes cannot hide metres of translation in its legs' heading drift. A drift that wanders rather
/// than runs at an even rate adds sigma_r x travel / sqrt(12) of independent position error (a random
/// walk's position given its end angle). Each closure adds the config's closure sigma (isotropic).
double CycleChi2(const ConsistencyClosure& a, const ConsistencyClosure& b, const ConsistencyOdometry& odometry,
                 const OdometryNoise& noise, const ClosureConsistencyConfig& config);

/// chi^2 (6 dof) of one closure against the odometry alone: the cycle T_query_ref * odom(ref -> query)
/// over one leg, under the same drift model. A closure the odometry contradicts where its drift bound
/// says it must agree (a short loop, a turned or shifted place of a repetitive world) is dropped
/// before any pairing: pairs of such closures can agree with each other.
double OdometryChi2(const ConsistencyClosure& closure, const ConsistencyOdometry& odometry, const OdometryNoise& noise,
                    const ClosureConsistencyConfig& config);

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
    /// earlier closure). Cost: one check against the odometry, one cycle per earlier closure, and a
    /// clique search among the new closure's consistent partners only when it disagrees with the
    /// current set. A closure the odometry contradicts (`OdometryChi2` above `odometry_chi2_threshold`) agrees
    /// with nothing.
    /// `may_displace` false (the proximity pass's closures): the closure joins the set only when it agrees
    /// with all of it, and the set is never re-solved around it, so it cannot displace a closure there.
    void Add(const ConsistencyClosure& closure, const ConsistencyOdometry& odometry, bool may_displace = true);
    /// One flag per added closure: in the maximum consistent set (ties: the larger sum of scores, then
    /// the closer agreement with the odometry alone), kept
    /// incrementally as closures arrive. A single closure is kept (nothing to check it against); with
    /// the check disabled every closure is kept.
    std::vector<char> ConsistentSet() const;

    std::size_t size() const { return closures_.size(); }
    /// The closure's chi^2 against the odometry alone (`OdometryChi2`).
    double OdometryChi2Of(std::size_t k) const { return odometry_chi2_[k]; }
    bool ContradictsOdometry(std::size_t k) const { return config_.enabled && odometry_chi2_[k] > config_.odometry_chi2_threshold; }
    bool Consistent(std::size_t a, std::size_t b) const { return consistent_[a][b] != 0; }
    const OdometryNoise& noise() const { return noise_; }

    /// [rad/m] The rotation drift the consistent set shows: the largest, over its closures, rotation angle of
    /// the closure's cycle with the odometry (`OdometryChi2`'s cycle) per metre of travel between its nodes;
    /// nullopt with fewer than `min_closures` closures in the set. The largest: a drift that wanders shows
    /// its rate on short legs and averages out on long ones (mit-killian: 2.2e-3 rad/m over 150 m, 7e-5
    /// over 1,200 m), and a wrong closure in the set can only keep the rate from being lowered.
    std::optional<double> ObservedRotationRate(const ConsistencyOdometry& odometry, std::size_t min_closures) const;
    /// The same closures added again, in their order and with their `may_displace`, under other drift noise.
    ClosureConsistency Rechecked(const OdometryNoise& noise, const ConsistencyOdometry& odometry) const;

  private:
    /// Ties between sets of equal size: the larger sum of scores, then the closer agreement with the odometry.
    double TieWeight(std::size_t k) const;

    ClosureConsistencyConfig config_;
    OdometryNoise noise_;
    std::vector<ConsistencyClosure> closures_;
    std::vector<std::vector<char>> consistent_;
    std::vector<char> in_set_;  ///< the maximum consistent set, kept up to date by Add
    std::vector<char> may_displace_;  ///< per closure, as added
    std::vector<double> odometry_chi2_;
    std::size_t set_size_ = 0;
    double set_weight_ = 0.0;
};

}  // namespace revisit
