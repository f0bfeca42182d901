#pragma once
/// SE(3) pose graph in Ceres: odometry chain plus robust loop-closure edges.
/// METHOD.md section 6: nodes are the local maps' first-scan poses, the first node is
/// fixed, loop edges carry a robust loss so that a wrong closure cannot bend the map.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <vector>

#include "core/trajectory.hpp"
#include "optimization/robust_loss.hpp"

namespace revisit {

using Matrix6d = Eigen::Matrix<double, 6, 6>;

/// A relative-pose measurement. The error is e = [R_m' (t_est - t_m); 2 vec(q_m^-1 q_est)]
/// with T_est = T_world_from^-1 T_world_to, i.e. to first order LogSE3(T_from_to^-1 T_est)
/// ordered [translation; rotation]; chi^2 = e' information e.
struct PoseGraphEdge {
    int from = 0;
    int to = 0;
    Eigen::Isometry3d T_from_to = Eigen::Isometry3d::Identity();  ///< measured pose of `to` in `from`
    Matrix6d information = Matrix6d::Identity();                  ///< [1/m^2, 1/rad^2] blocks; PSD
    bool is_loop = false;                                         ///< loop edges get the robust loss
};

struct PoseGraphConfig {
    /// Cauchy by default: its weight falls off as 1 / chi^2, so correct closures far from the
    /// drifted odometry still pull (measured: 13-15 iterations, same APE with 10-20% wrong
    /// closures). DCS needs `anneal` on drifted starts: without it, it switches off every closure.
    RobustLossKind loop_loss = RobustLossKind::kCauchy;
    double loop_loss_scale = 10.0;    ///< c (Cauchy) or Phi (DCS) on chi^2; ~ chi^2(6 dof) 88% quantile
    /// A loop edge costs nothing while its chi^2 is within this (ToleranceExcess): a closure the odometry
    /// already agrees with, within the closure's own uncertainty, does not pull the odometry off, and one
    /// it disagrees with pulls only until it agrees. 0: plain least squares under the kernel.
    double loop_tolerance_chi2 = 0.0;
    /// Graduated robustness: solve first with a wide kernel (scale = the largest initial loop
    /// chi^2, capped), then shrink it by `annealing_factor` per stage down to `loop_loss_scale`.
    /// Slower (5-20x the iterations); use it with DCS.
    bool anneal = false;
    double annealing_factor = 10.0;   ///< kernel shrink per stage (> 1)
    double max_annealing_scale = 1e6; ///< cap of the first stage's kernel scale
    int max_iterations = 100;         ///< Ceres iterations per stage
    double max_time_s = 0.0;          ///< [s] wall-time bound of the whole call; <= 0: none
    double function_tolerance = 1e-7; ///< Ceres relative cost change to stop
};

struct PoseGraphResult {
    Poses T_world_node;              ///< optimized node poses (unconnected nodes unchanged)
    std::vector<double> edge_weights;  ///< final robust weight rho'(chi^2) per edge, 1 for odometry
    std::vector<double> edge_chi2;     ///< final chi^2 per edge
    double initial_cost = 0.0;       ///< robust cost before the last stage
    double final_cost = 0.0;         ///< robust cost after the last stage
    int iterations = 0;              ///< Ceres iterations over all stages
    int stages = 0;                  ///< annealing stages run
    int anchored_nodes = 0;          ///< nodes held fixed: the first node of every connected piece
    bool hit_time_limit = false;     ///< stopped by `max_time_s` before converging
};

/// Optimizes the graph from the initial node poses. The first node of every connected
/// component is held fixed (gauge); nodes without edges keep their pose. Throws
/// std::out_of_range for an edge naming a node that does not exist or itself.
PoseGraphResult OptimizePoseGraph(const Poses& T_world_node_initial, const std::vector<PoseGraphEdge>& edges,
                                  const PoseGraphConfig& config);

/// Odometry edges between consecutive nodes, measured from the node poses themselves.
std::vector<PoseGraphEdge> OdometryEdges(const Poses& T_world_node, const Matrix6d& information);

/// Information matrix for independent noise: translation sigma [m], rotation sigma [rad].
Matrix6d DiagonalInformation(double sigma_translation, double sigma_rotation);

/// How much LiDAR odometry may drift, per metre travelled. Deliberately pessimistic: an
/// overconfident odometry makes the robust loss reject a lone correct closure.
struct OdometryNoise {
    double translation_per_m = 0.01;  ///< [m/m] 1% of the travelled distance
    double rotation_per_m = 3e-4;     ///< [rad/m] ~1.7 deg per 100 m
    double min_translation = 0.02;    ///< [m] floor for short steps
    double min_rotation = 0.002;      ///< [rad] floor for short steps
};

/// Information of an odometry edge spanning `travel_m` metres (sigma grows linearly: drift is
/// mostly systematic). 10 m with the defaults: sigma 0.1 m and 0.003 rad.
Matrix6d OdometryInformation(double travel_m, const OdometryNoise& noise = {});

/// The same measurement seen from the other end: from/to swapped, T_from_to inverted and the
/// information moved through the adjoint (delta' = -Ad(T_from_to) delta, so
/// Omega' = Ad^-T Omega Ad^-1), so chi^2 is unchanged to first order. Use it to turn a
/// refinement's (T_query_ref, information) into an edge from the reference node.
PoseGraphEdge InvertEdge(const PoseGraphEdge& edge);

/// chi^2 of one edge for the given node poses.
double EdgeChi2(const PoseGraphEdge& edge, const Eigen::Isometry3d& T_world_from, const Eigen::Isometry3d& T_world_to);

}  // namespace revisit
