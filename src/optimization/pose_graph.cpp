#include "optimization/pose_graph.hpp"

#include <ceres/ceres.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>
#include <utility>

#include "optimization/refinement.hpp"

namespace revisit {
namespace {

/// The unwhitened edge error e (see PoseGraphEdge), shared by the Ceres cost and EdgeChi2.
template <typename T>
Eigen::Matrix<T, 6, 1> EdgeError(const Eigen::Quaternion<T>& q_from, const Eigen::Matrix<T, 3, 1>& t_from,
                                 const Eigen::Quaternion<T>& q_to, const Eigen::Matrix<T, 3, 1>& t_to,
                                 const Eigen::Quaterniond& q_measured, const Eigen::Vector3d& t_measured) {
    const Eigen::Quaternion<T> q_from_inverse = q_from.conjugate();
    const Eigen::Quaternion<T> q_estimated = q_from_inverse * q_to;
    const Eigen::Matrix<T, 3, 1> t_estimated = q_from_inverse * (t_to - t_from);
    const Eigen::Quaternion<T> q_measured_inverse = q_measured.conjugate().cast<T>();
    Eigen::Quaternion<T> q_delta = q_measured_inverse * q_estimated;
    // q and -q are the same rotation: take the one with w >= 0 so that 2 vec(q) ~ the angle.
    if (q_delta.w() < T(0)) q_delta.coeffs() = -q_delta.coeffs();
    Eigen::Matrix<T, 6, 1> error;
    error.template head<3>() = q_measured_inverse * (t_estimated - t_measured.cast<T>());
    error.template tail<3>() = T(2) * q_delta.vec();
    return error;
}

struct EdgeCost {
    EdgeCost(const Eigen::Isometry3d& T_from_to, const Matrix6d& sqrt_information)
        : q_measured_(T_from_to.linear()), t_measured_(T_from_to.translation()), sqrt_information_(sqrt_information) {}

    template <typename T>
    bool operator()(const T* q_from, const T* t_from, const T* q_to, const T* t_to, T* residual) const {
        const Eigen::Matrix<T, 6, 1> error =
            EdgeError(Eigen::Quaternion<T>(q_from), Eigen::Matrix<T, 3, 1>(t_from), Eigen::Quaternion<T>(q_to),
                      Eigen::Matrix<T, 3, 1>(t_to), q_measured_, t_measured_);
        Eigen::Map<Eigen::Matrix<T, 6, 1>> whitened(residual);
        whitened = sqrt_information_.cast<T>() * error;
        return true;
    }

    Eigen::Quaterniond q_measured_;
    Eigen::Vector3d t_measured_;
    Matrix6d sqrt_information_;
};

/// S with S'S = information, for positive semi-definite information (eigen decomposition,
/// so a rank-deficient registration information is accepted).
Matrix6d SqrtInformation(const Matrix6d& information) {
    const Eigen::SelfAdjointEigenSolver<Matrix6d> solver(0.5 * (information + information.transpose()));
    const Eigen::Matrix<double, 6, 1> roots = solver.eigenvalues().cwiseMax(0.0).cwiseSqrt();
    return roots.asDiagonal() * solver.eigenvectors().transpose();
}

struct NodeState {
    Eigen::Quaterniond q;
    Eigen::Vector3d t;
};

/// Union-find root of each node, for the connected pieces of the graph.
std::vector<int> ComponentRoots(int num_nodes, const std::vector<PoseGraphEdge>& edges) {
    std::vector<int> parent(static_cast<std::size_t>(num_nodes));
    std::iota(parent.begin(), parent.end(), 0);
    auto find = [&](int i) {
        while (parent[i] != i) i = parent[i] = parent[parent[i]];
        return i;
    };
    for (const auto& edge : edges) {
        const int a = find(edge.from);
        const int b = find(edge.to);
        if (a != b) parent[std::max(a, b)] = std::min(a, b);  // the root is the piece's first node
    }
    std::vector<int> roots(parent.size());
    for (int i = 0; i < num_nodes; ++i) roots[i] = find(i);
    return roots;
}

void ValidateEdges(int num_nodes, const std::vector<PoseGraphEdge>& edges) {
    for (std::size_t k = 0; k < edges.size(); ++k) {
        const auto& edge = edges[k];
        if (edge.from < 0 || edge.to < 0 || edge.from >= num_nodes || edge.to >= num_nodes || edge.from == edge.to)
            throw std::out_of_range("pose graph edge " + std::to_string(k) + " joins nodes " + std::to_string(edge.from) +
                                    " and " + std::to_string(edge.to) + " of " + std::to_string(num_nodes));
    }
}

/// Kernel scales of the stages, widest first, ending at config.loop_loss_scale.
std::vector<double> AnnealingScales(const std::vector<double>& loop_chi2, const PoseGraphConfig& config) {
    std::vector<double> scales;
    if (config.anneal && config.loop_loss != RobustLossKind::kNone && !loop_chi2.empty() && config.annealing_factor > 1.0) {
        const double widest = std::min(config.max_annealing_scale, *std::max_element(loop_chi2.begin(), loop_chi2.end()));
        for (double scale = widest; scale > config.loop_loss_scale; scale /= config.annealing_factor) scales.push_back(scale);
    }
    scales.push_back(config.loop_loss_scale);
    return scales;
}

Eigen::Isometry3d ToIsometry(const NodeState& node) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = node.q.normalized().toRotationMatrix();
    T.translation() = node.t;
    return T;
}

}  // namespace

double EdgeChi2(const PoseGraphEdge& edge, const Eigen::Isometry3d& T_world_from, const Eigen::Isometry3d& T_world_to) {
    const Eigen::Matrix<double, 6, 1> error = EdgeError(Eigen::Quaterniond(T_world_from.linear()), Eigen::Vector3d(T_world_from.translation()),
                                         Eigen::Quaterniond(T_world_to.linear()), Eigen::Vector3d(T_world_to.translation()),
                                         Eigen::Quaterniond(edge.T_from_to.linear()), edge.T_from_to.translation());
    return error.dot(edge.information * error);
}

Matrix6d DiagonalInformation(double sigma_translation, double sigma_rotation) {
    Eigen::Matrix<double, 6, 1> diagonal;
    diagonal << Eigen::Vector3d::Constant(1.0 / (sigma_translation * sigma_translation)),
        Eigen::Vector3d::Constant(1.0 / (sigma_rotation * sigma_rotation));
    return diagonal.asDiagonal();
}

PoseGraphEdge InvertEdge(const PoseGraphEdge& edge) {
    // Adjoint of T = (R, t) for the [translation; rotation] ordering: [[R, [t]x R], [0, R]].
    const Eigen::Matrix3d R = edge.T_from_to.linear();
    const Eigen::Vector3d t = edge.T_from_to.translation();
    Eigen::Matrix3d t_hat;
    t_hat << 0, -t.z(), t.y(), t.z(), 0, -t.x(), -t.y(), t.x(), 0;
    Matrix6d adjoint = Matrix6d::Zero();
    adjoint.topLeftCorner<3, 3>() = R;
    adjoint.topRightCorner<3, 3>() = t_hat * R;
    adjoint.bottomRightCorner<3, 3>() = R;
    const Matrix6d adjoint_inverse = adjoint.inverse();
    PoseGraphEdge inverted = edge;
    std::swap(inverted.from, inverted.to);
    inverted.T_from_to = edge.T_from_to.inverse();
    inverted.information = adjoint_inverse.transpose() * edge.information * adjoint_inverse;
    return inverted;
}

Matrix6d OdometryInformation(double travel_m, const OdometryNoise& noise) {
    return DiagonalInformation(std::max(noise.min_translation, noise.translation_per_m * travel_m),
                               std::max(noise.min_rotation, noise.rotation_per_m * travel_m));
}

std::vector<PoseGraphEdge> OdometryEdges(const Poses& T_world_node, const Matrix6d& information) {
    std::vector<PoseGraphEdge> edges;
    for (std::size_t i = 1; i < T_world_node.size(); ++i) {
        edges.push_back({static_cast<int>(i - 1), static_cast<int>(i), T_world_node[i - 1].inverse() * T_world_node[i],
                         information, false});
    }
    return edges;
}

PoseGraphResult OptimizePoseGraph(const Poses& T_world_node_initial, const std::vector<PoseGraphEdge>& edges,
                                  const PoseGraphConfig& config) {
    const auto start_time = std::chrono::steady_clock::now();
    const int num_nodes = static_cast<int>(T_world_node_initial.size());
    ValidateEdges(num_nodes, edges);
    PoseGraphResult result;
    result.T_world_node = T_world_node_initial;
    result.edge_weights.assign(edges.size(), 1.0);
    result.edge_chi2.assign(edges.size(), 0.0);
    if (edges.empty()) return result;

    std::vector<NodeState> nodes;
    nodes.reserve(T_world_node_initial.size());
    for (const auto& T : T_world_node_initial) nodes.push_back({Eigen::Quaterniond(T.linear()).normalized(), T.translation()});

    // Loop edges share one loss through a wrapper whose kernel each annealing stage swaps.
    ceres::LossFunctionWrapper loop_loss(nullptr, ceres::TAKE_OWNERSHIP);
    ceres::Problem::Options problem_options;
    problem_options.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
    problem_options.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
    ceres::EigenQuaternionManifold quaternion_manifold;  // outlives the problem that borrows it
    ceres::Problem problem(problem_options);
    std::vector<double> loop_chi2;
    for (const auto& edge : edges) {
        NodeState& from = nodes[static_cast<std::size_t>(edge.from)];
        NodeState& to = nodes[static_cast<std::size_t>(edge.to)];
        auto* cost = new ceres::AutoDiffCostFunction<EdgeCost, 6, 4, 3, 4, 3>(new EdgeCost(edge.T_from_to, SqrtInformation(edge.information)));
        problem.AddResidualBlock(cost, edge.is_loop ? &loop_loss : nullptr, from.q.coeffs().data(), from.t.data(),
                                 to.q.coeffs().data(), to.t.data());
        if (edge.is_loop) loop_chi2.push_back(ToleranceExcess(EdgeChi2(edge, ToIsometry(from), ToIsometry(to)), config.loop_tolerance_chi2));
    }
    const auto roots = ComponentRoots(num_nodes, edges);
    for (int i = 0; i < num_nodes; ++i) {
        NodeState& node = nodes[static_cast<std::size_t>(i)];
        if (!problem.HasParameterBlock(node.q.coeffs().data())) continue;
        problem.SetManifold(node.q.coeffs().data(), &quaternion_manifold);
        if (roots[i] == i) {  // the first node of each connected piece fixes that piece's gauge
            problem.SetParameterBlockConstant(node.q.coeffs().data());
            problem.SetParameterBlockConstant(node.t.data());
            ++result.anchored_nodes;
        }
    }

    ceres::Solver::Options options;
    options.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
    options.max_num_iterations = config.max_iterations;
    options.function_tolerance = config.function_tolerance;
    options.num_threads = CeresThreadCount();
    options.logging_type = ceres::SILENT;
    for (const double scale : AnnealingScales(loop_chi2, config)) {
        if (config.max_time_s > 0.0) {
            const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_time).count();
            options.max_solver_time_in_seconds = config.max_time_s - elapsed;
            if (options.max_solver_time_in_seconds <= 0.0) {
                result.hit_time_limit = true;
                break;
            }
        }
        loop_loss.Reset(MakeLoopLoss(config.loop_loss, scale, config.loop_tolerance_chi2).release(), ceres::TAKE_OWNERSHIP);
        ceres::Solver::Summary summary;
        ceres::Solve(options, &problem, &summary);
        result.iterations += std::max(0, static_cast<int>(summary.iterations.size()) - 1);  // entry 0 is the start
        result.initial_cost = summary.initial_cost;
        result.final_cost = summary.final_cost;
        result.hit_time_limit = summary.termination_type == ceres::NO_CONVERGENCE &&
                                summary.message.find("time") != std::string::npos;
        ++result.stages;
    }

    for (int i = 0; i < num_nodes; ++i) result.T_world_node[i] = ToIsometry(nodes[static_cast<std::size_t>(i)]);
    for (std::size_t k = 0; k < edges.size(); ++k) {
        const auto& edge = edges[k];
        result.edge_chi2[k] = EdgeChi2(edge, result.T_world_node[edge.from], result.T_world_node[edge.to]);
        if (edge.is_loop)
            result.edge_weights[k] = LoopWeight(config.loop_loss, config.loop_loss_scale, config.loop_tolerance_chi2, result.edge_chi2[k]);
    }
    return result;
}

}  // namespace revisit
