#include "optimization/refinement.hpp"

#include <ceres/ceres.h>
#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <deque>
#include <limits>
#include <optional>
#include <tuple>
#include <utility>
#include <tsl/robin_set.h>

#include "core/error.hpp"
#include "core/se3.hpp"
#include "optimization/point_grid.hpp"

namespace revisit {
namespace {

/// A query-map point usable as a plane: its position and unit normal.
using Plane = RefinementQuery::Plane;

struct Correspondence {
    Eigen::Vector3d source;  ///< reference-map point, in the reference frame
    Eigen::Vector3d target;  ///< query-map plane point
    Eigen::Vector3d normal;  ///< query-map plane normal
};

/// r = n . (T_start * T(delta) * p - q): signed distance of the moved reference point to the
/// query plane, with T(delta) = (ExpSO3(delta_rot), delta_trans) a right update of the
/// linearization pose. Analytic Jacobian: autodiff through a quaternion cost ~3x more per point.
class PointToPlaneCost : public ceres::SizedCostFunction<1, 6> {
  public:
    PointToPlaneCost(const Correspondence& c, const Eigen::Isometry3d& T_start) : c_(c), T_start_(&T_start) {}
    bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override {
        const Eigen::Map<const Eigen::Matrix<double, 6, 1>> delta(parameters[0]);
        const Eigen::Matrix3d R_delta = ExpSO3(delta.tail<3>());
        const Eigen::Vector3d rotated = R_delta * c_.source;
        residuals[0] = c_.normal.dot(*T_start_ * (rotated + delta.head<3>()) - c_.target);
        if (jacobians != nullptr && jacobians[0] != nullptr) {
            const Eigen::Vector3d n_in_start = T_start_->linear().transpose() * c_.normal;
            Eigen::Map<Eigen::Matrix<double, 1, 6>> J(jacobians[0]);
            J.head<3>() = n_in_start.transpose();
            // d/d(rot) of n' R_delta exp([w]) p at w = 0: (p x R_delta' n')'.
            J.tail<3>() = c_.source.cross(R_delta.transpose() * n_in_start).transpose();
        }
        return true;
    }

  private:
    Correspondence c_;
    const Eigen::Isometry3d* T_start_;
};

void Validate(const RefinementConfig& config) {
    if (!(config.voxel_size > 0.0) || !(config.normal_radius > 0.0) || !(config.overlap_voxel_size > 0.0))
        throw ConfigError("refinement: voxel_size, normal_radius and overlap_voxel_size must be positive");
    if (!(config.max_correspondence_distance > 0.0) || config.initial_max_distance < config.max_correspondence_distance)
        throw ConfigError("refinement: need 0 < max_correspondence_distance <= initial_max_distance");
    if (config.max_iterations < 1 || config.max_solver_iterations < 1)
        throw ConfigError("refinement: max_iterations and max_solver_iterations must be >= 1");
}

/// The lowest and highest point along `up` (unit). A 2D laser's maps have every point at one height: a
/// wall is then a line, whose 3D neighbourhood has two zero eigenvalues, and the smallest one's
/// eigenvector may be the vertical, a normal that constrains nothing in the plane.
std::pair<double, double> HeightRange(const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& unit_up) {
    double low = std::numeric_limits<double>::infinity(), high = -low;
    for (const auto& p : points) {
        low = std::min(low, unit_up.dot(p));
        high = std::max(high, unit_up.dot(p));
    }
    return {low, high};
}
/// The planes' points, in order: what their grids are built from (only when a grid is built; the
/// proximity pass's query keeps its grids for many registrations).
std::vector<Eigen::Vector3d> PointsOf(const std::vector<Plane>& planes) {
    std::vector<Eigen::Vector3d> points;
    points.reserve(planes.size());
    for (const auto& plane : planes) points.push_back(plane.point);
    return points;
}

constexpr double kOneHeight = 1e-6;  ///< [m] spread along up below which points lie at one height

/// Planes of the query map: PCA normal of each point's neighbourhood, kept only where the
/// neighbourhood is flat (surface variation, Pauly et al. 2002) and populated enough. With
/// `in_plane_up` nonzero (a planar map) the PCA is taken within the plane orthogonal to it: the normal
/// of a wall line, and its variation among the two in-plane directions.
std::vector<Plane> EstimatePlanes(const std::vector<Eigen::Vector3d>& points, const RefinementConfig& config,
                                  const Eigen::Vector3d& in_plane_up) {
    const PointGrid grid(points, config.normal_radius);
    const auto& sorted = grid.sorted_points();
    const double radius_squared = config.normal_radius * config.normal_radius;
    std::vector<std::optional<Plane>> planes(points.size());
    // Cell by cell: the points of one cell share their 27 neighbour cells, looked up once. The sums run
    // over the same points in the same order as a per-point radius query.
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, grid.num_cells()), [&](const auto& range) {
        std::vector<std::uint32_t> neighbours;
        for (std::size_t cell = range.begin(); cell != range.end(); ++cell) {
            grid.NeighbourCells(cell, config.normal_radius, neighbours);
            for (std::size_t own = grid.CellBegin(cell); own < grid.CellEnd(cell); ++own) {
                const Eigen::Vector3d& point = sorted[own];
                // One pass, relative to the point itself (small numbers, no cancellation).
                int count = 0;
                Eigen::Vector3d sum_offset = Eigen::Vector3d::Zero();
                Eigen::Matrix3d sum_outer = Eigen::Matrix3d::Zero();
                for (const std::uint32_t other : neighbours)
                    for (std::size_t slot = grid.CellBegin(other); slot < grid.CellEnd(other); ++slot) {
                        const Eigen::Vector3d d = sorted[slot] - point;
                        if (d.squaredNorm() > radius_squared) continue;
                        ++count;
                        sum_offset += d;
                        sum_outer.noalias() += d * d.transpose();
                    }
                if (count < config.min_normal_neighbours) continue;
                const Eigen::Vector3d mean = sum_offset / count;
                Eigen::Matrix3d covariance = sum_outer / count - mean * mean.transpose();
                // Planar: the vertical gets the largest eigenvalue, so the smallest is the in-plane normal.
                const double vertical_weight = covariance.trace() + 1.0;
                if (in_plane_up.squaredNorm() > 0.0) covariance += vertical_weight * in_plane_up * in_plane_up.transpose();
                const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(covariance);
                double sum = solver.eigenvalues().sum();
                if (in_plane_up.squaredNorm() > 0.0) sum -= vertical_weight;
                if (!(sum > 0.0) || solver.eigenvalues()(0) / sum > config.max_surface_variation) continue;
                planes[std::size_t(grid.index()[own])] = Plane{point, solver.eigenvectors().col(0)};
            }
        }
    });
    std::vector<Plane> kept;
    for (const auto& plane : planes)
        if (plane) kept.push_back(*plane);
    return kept;
}

/// Nearest query plane within `gate` of each moved reference point (TBB, order kept).
std::vector<Correspondence> FindCorrespondences(const std::vector<Eigen::Vector3d>& source, const std::vector<Plane>& planes,
                                                const PointGrid& plane_grid, const Eigen::Isometry3d& T_query_ref, double gate) {
    std::vector<int> match(source.size(), -1);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, source.size()), [&](const auto& range) {
        for (std::size_t i = range.begin(); i != range.end(); ++i) match[i] = plane_grid.FindNearest(T_query_ref * source[i], gate);
    });
    std::vector<Correspondence> found;
    found.reserve(source.size());
    for (std::size_t i = 0; i < source.size(); ++i) {
        if (match[i] < 0) continue;
        const Plane& plane = planes[static_cast<std::size_t>(match[i])];
        found.push_back({source[i], plane.point, plane.normal});
    }
    return found;
}

/// One robust Levenberg-Marquardt solve of the point-to-plane problem for fixed
/// correspondences, over a right update of `T_start` (no manifold needed: the update is
/// re-based every outer iteration).
Eigen::Isometry3d SolvePointToPlane(const std::vector<Correspondence>& correspondences, const Eigen::Isometry3d& T_start,
                                    const RefinementConfig& config) {
    std::deque<PointToPlaneCost> costs;  // cost functions cannot move: a deque never relocates
    for (const auto& c : correspondences) costs.emplace_back(c, T_start);
    // Costs and the one loss live here; the problem only borrows them (no per-point allocation).
    ceres::CauchyLoss loss(config.loss_scale);
    ceres::Problem::Options problem_options;
    problem_options.cost_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
    problem_options.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
    ceres::Problem problem(problem_options);
    Eigen::Matrix<double, 6, 1> delta = Eigen::Matrix<double, 6, 1>::Zero();
    for (auto& cost : costs) problem.AddResidualBlock(&cost, &loss, delta.data());
    ceres::Solver::Options options;
    options.linear_solver_type = ceres::DENSE_NORMAL_CHOLESKY;
    options.max_num_iterations = config.max_solver_iterations;
    options.num_threads = CeresThreadCount();
    options.logging_type = ceres::SILENT;
    ceres::Solver::Summary summary;
    ceres::Solve(options, &problem, &summary);
    Eigen::Isometry3d update = Eigen::Isometry3d::Identity();
    update.linear() = ExpSO3(delta.tail<3>());
    update.translation() = delta.head<3>();
    return T_start * update;
}

/// Residual RMS and information J^T J / sigma^2 for a right perturbation of T_query_ref.
void MeasureFit(const std::vector<Correspondence>& correspondences, const RefinementConfig& config, RefinementResult& result) {
    const Eigen::Matrix3d R = result.T_query_ref.linear();
    double squared_sum = 0.0;
    Matrix6d hessian = Matrix6d::Zero();
    for (const auto& c : correspondences) {
        const double r = c.normal.dot(result.T_query_ref * c.source - c.target);
        squared_sum += r * r;
        // d r / d delta for T * ExpSE3(delta): [ (R^T n)^T , (p x R^T n)^T ].
        Eigen::Matrix<double, 6, 1> jacobian;
        const Eigen::Vector3d n_in_ref = R.transpose() * c.normal;
        jacobian << n_in_ref, c.source.cross(n_in_ref);
        hessian += jacobian * jacobian.transpose();
    }
    result.num_correspondences = static_cast<int>(correspondences.size());
    result.rms = correspondences.empty() ? 0.0 : std::sqrt(squared_sum / static_cast<double>(correspondences.size()));
    const double sigma = std::max(result.rms, config.min_point_sigma);
    result.information = hessian / (sigma * sigma);
    if (config.information_effective_points > 0.0 && !correspondences.empty())
        result.information *= config.information_effective_points / static_cast<double>(correspondences.size());
}

std::string Describe(const char* what, double value, const char* relation, double threshold) {
    char buffer[160];
    std::snprintf(buffer, sizeof(buffer), "%s %.3g %s %.3g", what, value, relation, threshold);
    return buffer;
}

/// The first failed acceptance test, or an empty string.
std::string Judge(const RefinementResult& result, const Eigen::Isometry3d& T_guess, const RefinementConfig& config) {
    if (result.num_correspondences < config.min_correspondences)
        return Describe("correspondences", result.num_correspondences, "below", config.min_correspondences);
    if (result.overlap < config.min_overlap) return Describe("overlap", result.overlap, "below", config.min_overlap);
    if (result.rms > config.max_rms) return Describe("rms [m]", result.rms, "above", config.max_rms);
    const Eigen::Isometry3d correction = T_guess.inverse() * result.T_query_ref;
    const std::string moved = kCorrectionFromGuess;
    if (correction.translation().norm() > config.max_correction_translation)
        return Describe((moved + " [m]").c_str(), correction.translation().norm(), "above", config.max_correction_translation);
    const double angle = Eigen::AngleAxisd(correction.linear()).angle();
    if (angle > config.max_correction_rotation)
        return Describe((moved + " [rad]").c_str(), angle, "above", config.max_correction_rotation);
    return {};
}

/// The guess moved along `up` by the offset (steps of the voxel, within +-range) under which the most
/// reference voxels land on occupied query voxels; ties keep the smaller offset (scan order).
Eigen::Isometry3d SearchVertical(const std::vector<Eigen::Vector3d>& source, const std::vector<Eigen::Vector3d>& query,
                                 const Eigen::Isometry3d& T_guess, const Eigen::Vector3d& up, double range, double voxel) {
    if (!(range > 0.0) || up.squaredNorm() == 0.0) return T_guess;
    tsl::robin_set<Voxel, VoxelHash> occupied;
    occupied.reserve(query.size());
    for (const auto& q : query) occupied.insert(VoxelOf(q, voxel));
    std::vector<Eigen::Vector3d> moved(source.size());
    for (std::size_t i = 0; i < source.size(); ++i) moved[i] = T_guess * source[i];
    const Eigen::Vector3d unit_up = up.normalized();
    const int steps = static_cast<int>(std::floor(range / voxel));
    int best_count = -1;
    double best_offset = 0.0;
    for (int k = 0; k <= 2 * steps; ++k) {
        const int signed_step = (k + 1) / 2 * (k % 2 == 1 ? 1 : -1);  // 0, +1, -1, +2, -2, ...
        const Eigen::Vector3d shift = unit_up * (signed_step * voxel);
        int count = 0;
        for (const auto& p : moved) count += occupied.count(VoxelOf(p + shift, voxel)) != 0 ? 1 : 0;
        if (count > best_count) {
            best_count = count;
            best_offset = signed_step * voxel;
        }
    }
    Eigen::Isometry3d result = T_guess;
    result.translation() += unit_up * best_offset;
    return result;
}

}  // namespace

int CeresThreadCount() {
    return static_cast<int>(std::max<std::size_t>(1, tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism)));
}

RefinementQuery::RefinementQuery(const std::vector<Eigen::Vector3d>& query_points_in_query, const RefinementConfig& config,
                                 const Eigen::Vector3d& up_in_query)
    : points_(VoxelDownsample(query_points_in_query, config.voxel_size)),
      up_(up_in_query),
      voxel_size_(config.voxel_size),
      normal_radius_(config.normal_radius),
      max_surface_variation_(config.max_surface_variation),
      min_normal_neighbours_(config.min_normal_neighbours) {
    Validate(config);
    if (up_.squaredNorm() > 0.0) {
        std::tie(low_, high_) = HeightRange(points_, up_.normalized());
        planar_ = !points_.empty() && high_ - low_ < kOneHeight;
    }
    planes_ = EstimatePlanes(points_, config, planar_ ? Eigen::Vector3d(up_.normalized()) : Eigen::Vector3d::Zero());
}

const PointGrid& RefinementQuery::PlaneGrid(double gate, std::optional<PointGrid>& built) const {
    if (!keep_grids_) return built.emplace(PointsOf(planes_), gate);
    for (const auto& [kept_gate, grid] : grids_)
        if (kept_gate == gate) return *grid;
    grids_.emplace_back(gate, std::make_unique<PointGrid>(PointsOf(planes_), gate));
    return *grids_.back().second;
}

bool RefinementQuery::MadeWith(const RefinementConfig& config) const {
    return config.voxel_size == voxel_size_ && config.normal_radius == normal_radius_ &&
           config.max_surface_variation == max_surface_variation_ && config.min_normal_neighbours == min_normal_neighbours_;
}

bool RefinementQuery::SamePlanesAs(const Eigen::Vector3d& up_in_query) const {
    bool planar = false;  // as the constructor decides it
    if (up_in_query.squaredNorm() > 0.0) {
        const auto [low, high] = HeightRange(points_, up_in_query.normalized());
        planar = !points_.empty() && high - low < kOneHeight;
    }
    if (planar != planar_) return false;
    return !planar || up_in_query.normalized() == up_.normalized();
}

RefinementResult RefineAlignment(const std::vector<Eigen::Vector3d>& ref_points_in_ref,
                                 const std::vector<Eigen::Vector3d>& query_points_in_query,
                                 const Eigen::Isometry3d& T_query_ref_guess, const RefinementConfig& config,
                                 const Eigen::Vector3d& up_in_query) {
    Validate(config);
    if (ref_points_in_ref.empty() || query_points_in_query.empty()) {
        RefinementResult result;
        result.T_query_ref = T_query_ref_guess;
        result.reason = "empty map";
        return result;
    }
    return RefineAlignment(ref_points_in_ref, RefinementQuery(query_points_in_query, config, up_in_query), T_query_ref_guess,
                           config);
}

RefinementResult RefineAlignment(const std::vector<Eigen::Vector3d>& ref_points_in_ref, const RefinementQuery& query,
                                 const Eigen::Isometry3d& T_query_ref_guess, const RefinementConfig& config) {
    Validate(config);
    if (!query.MadeWith(config)) throw ConfigError("refinement: the prepared query map was made with other settings");
    RefinementResult result;
    result.T_query_ref = T_query_ref_guess;
    if (ref_points_in_ref.empty() || query.points().empty()) {
        result.reason = "empty map";
        return result;
    }
    const auto source = VoxelDownsample(ref_points_in_ref, config.voxel_size);
    const auto& query_down = query.points();
    const Eigen::Vector3d& up_in_query = query.up();
    // Planar when both maps lie at one height (the same one); the prepared planes assumed the query's own.
    bool planar = false;
    if (query.planar()) {
        const auto [low, high] = HeightRange(source, up_in_query.normalized());
        planar = std::max(high, query.high()) - std::min(low, query.low()) < kOneHeight;
    }
    const bool own_planes = planar == query.planar();
    std::vector<Plane> replanned;
    if (!own_planes)
        replanned = EstimatePlanes(query_down, config, planar ? Eigen::Vector3d(up_in_query.normalized()) : Eigen::Vector3d::Zero());
    const std::vector<Plane>& planes = own_planes ? query.planes() : replanned;
    const Eigen::Isometry3d T_start = SearchVertical(source, query_down, T_query_ref_guess, up_in_query,
                                                     config.vertical_search, config.voxel_size);
    result.T_query_ref = T_start;

    // ICP runs on a fixed, evenly strided subset of the reference map (speed); the verdict uses all of it.
    const std::size_t stride = 1 + source.size() / static_cast<std::size_t>(std::max(1, config.max_solver_points));
    std::vector<Eigen::Vector3d> solve_source;
    for (std::size_t i = 0; i < source.size(); i += stride) solve_source.push_back(source[i]);

    // A grid with the gate as cell edge answers every query from 27 cells; rebuilt only while the gate
    // shrinks (the first `gate_decay_iterations`).
    std::optional<PointGrid> plane_grid;
    const PointGrid* grid = nullptr;
    double grid_gate = 0.0;
    const auto grid_for = [&](double gate) -> const PointGrid& {
        if (!grid || gate != grid_gate) {
            // Replanned planes are this registration's own: their grids are never the query's to keep.
            grid = own_planes ? &query.PlaneGrid(gate, plane_grid) : &plane_grid.emplace(PointsOf(planes), gate);
            grid_gate = gate;
        }
        return *grid;
    };
    std::vector<Correspondence> correspondences;
    for (int iteration = 0; iteration < config.max_iterations; ++iteration) {
        // The gate shrinks from the guess' error scale to the fine threshold (coarse-to-fine).
        const double progress = std::min(1.0, static_cast<double>(iteration) / std::max(1, config.gate_decay_iterations));
        const double gate = config.initial_max_distance + progress * (config.max_correspondence_distance - config.initial_max_distance);
        correspondences = FindCorrespondences(solve_source, planes, grid_for(gate), result.T_query_ref, gate);
        result.iterations = iteration + 1;
        if (static_cast<int>(correspondences.size()) < std::max(6, config.min_correspondences)) break;
        const Eigen::Isometry3d T_new = SolvePointToPlane(correspondences, result.T_query_ref, config);
        const Eigen::Isometry3d update = result.T_query_ref.inverse() * T_new;
        result.T_query_ref = T_new;
        const bool small = update.translation().norm() < config.convergence_translation &&
                           Eigen::AngleAxisd(update.linear()).angle() < config.convergence_rotation;
        if (small && progress >= 1.0) {
            result.converged = true;
            break;
        }
    }
    correspondences = FindCorrespondences(source, planes, grid_for(config.max_correspondence_distance), result.T_query_ref,
                                          config.max_correspondence_distance);
    MeasureFit(correspondences, config, result);
    std::vector<Eigen::Vector3d> moved(source.size());
    for (std::size_t i = 0; i < source.size(); ++i) moved[i] = result.T_query_ref * source[i];
    result.overlap = VoxelOverlap(moved, query_down, config.overlap_voxel_size);
    result.reason = Judge(result, T_start, config);
    result.accepted = result.reason.empty();
    if (result.num_correspondences < 6) result.information.setZero();
    return result;
}

}  // namespace revisit
