#include "odometry/registration.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <cmath>
#include <limits>
#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include "core/se3.hpp"
#include "odometry/anderson.hpp"

namespace revisit {
namespace {

using Matrix6d = Eigen::Matrix<double, 6, 6>;

/// Point-to-plane correspondences alone are used when every translation direction carries at least
/// this share of their weighted normals (the smallest eigenvalue of sum w n n^T / sum w; 1/3 when the
/// normals point every way equally): then the planes pin the frame down, and the non-planar
/// correspondences, whose point-to-point pull is biased where rings are sparse, are left out.
/// Measured smallest shares: real KITTI 0.07-0.08, a simulated 16-beam city 0.026-0.19.
constexpr double kMinPlaneDirectionShare = 0.02;

Eigen::Matrix3d Hat(const Eigen::Vector3d& v) {
    Eigen::Matrix3d m;
    m << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
    return m;
}

/// Weighted sums from which the normal equations are assembled. With J = [I, -hat(p)] (left
/// perturbation of the point p), J^T J and J^T r need only these moments, so a point costs a
/// few dozen flops instead of a 6x6 outer product.
struct Moments {
    double w = 0.0;                                       ///< sum w
    Eigen::Vector3d wp = Eigen::Vector3d::Zero();         ///< sum w p
    Eigen::Matrix3d wppt = Eigen::Matrix3d::Zero();       ///< sum w p p^T
    Eigen::Vector3d wr = Eigen::Vector3d::Zero();         ///< sum w r
    Eigen::Vector3d wpxr = Eigen::Vector3d::Zero();       ///< sum w p x r
    // Point-to-plane correspondences (residual e = n^T r, Jacobian row j = [n; p x n]): summed directly.
    Matrix6d wjjt = Matrix6d::Zero();                     ///< sum w j j^T
    Vector6d wje = Vector6d::Zero();                      ///< sum w j e
    double cost = 0.0;        ///< sum of the Geman-McClure costs k s / (k + s), s = |r|^2 (or e^2)
    double plane_cost = 0.0;  ///< the same over the point-to-plane correspondences
    std::size_t count = 0;
    std::size_t plane_count = 0;

    Moments& operator+=(const Moments& other) {
        w += other.w;
        wp += other.wp;
        wppt += other.wppt;
        wr += other.wr;
        wpxr += other.wpxr;
        wjjt += other.wjjt;
        wje += other.wje;
        cost += other.cost;
        plane_cost += other.plane_cost;
        count += other.count;
        plane_count += other.plane_count;
        return *this;
    }
};

Moments Accumulate(const std::vector<Eigen::Vector3d>& points, const VoxelHashMap& map, const Eigen::Isometry3d& T,
                   const Eigen::Vector3d& centre, const IcpParams& params,
                   std::vector<VoxelHashMap::Neighbourhood>& neighbourhoods) {
    const double k2 = params.kernel * params.kernel;
    // Deterministic reduce: the split tree depends only on the range and grain, never on the
    // thread count, so the floating-point sums are identical with 1 or N threads.
    return tbb::parallel_deterministic_reduce(
        tbb::blocked_range<std::size_t>(0, points.size(), 256), Moments{},
        [&](const tbb::blocked_range<std::size_t>& range, Moments sums) {
            for (std::size_t i = range.begin(); i != range.end(); ++i) {
                const Eigen::Vector3d p_world = T * points[i];
                const Eigen::Vector3d* nearest = map.FindNearest(p_world, params.max_correspondence_distance, neighbourhoods[i]);
                if (nearest == nullptr) continue;
                const Eigen::Vector3d r = p_world - *nearest;
                const Eigen::Vector3d p = p_world - centre;  // linearize about the sensor: better conditioned
                ++sums.count;
                const Eigen::Vector3d* normal = params.point_to_plane ? map.NormalOf(nearest) : nullptr;
                if (normal != nullptr) {
                    const double e = normal->dot(r);
                    const double denominator = params.kernel + e * e;
                    const double w = k2 / (denominator * denominator);
                    if (params.anderson_depth > 0) sums.plane_cost += params.kernel * e * e / denominator;
                    Vector6d j;
                    j << *normal, p.cross(*normal);
                    sums.wjjt.noalias() += (w * j) * j.transpose();
                    sums.wje += (w * e) * j;
                    ++sums.plane_count;
                    continue;
                }
                const double denominator = params.kernel + r.squaredNorm();
                const double w = k2 / (denominator * denominator);
                if (params.anderson_depth > 0) sums.cost += params.kernel * r.squaredNorm() / denominator;
                sums.w += w;
                sums.wp += w * p;
                sums.wppt.noalias() += (w * p) * p.transpose();
                sums.wr += w * r;
                sums.wpxr += w * p.cross(r);
            }
            return sums;
        },
        [](Moments a, const Moments& b) { return a += b; });
}

/// Whether the point-to-plane correspondences alone constrain every translation direction.
bool PlanesSuffice(const Moments& m) {
    const Eigen::Matrix3d normals = m.wjjt.topLeftCorner<3, 3>();
    const double total = normals.trace();
    if (!(total > 0.0)) return false;
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver;
    solver.computeDirect(normals / total, Eigen::EigenvaluesOnly);
    return solver.eigenvalues()[0] >= kMinPlaneDirectionShare;
}

/// J^T J and J^T r from the moments (J = [I, -hat(p)], tangent order [rho; phi]); only the
/// point-to-plane sums when `planes_only`.
void AssembleNormalEquations(const Moments& m, bool planes_only, Matrix6d& JTJ, Vector6d& JTr) {
    if (planes_only) {
        JTJ = m.wjjt;
        JTr = m.wje;
        return;
    }
    JTJ.topLeftCorner<3, 3>() = m.w * Eigen::Matrix3d::Identity();
    JTJ.topRightCorner<3, 3>() = -Hat(m.wp);
    JTJ.bottomLeftCorner<3, 3>() = Hat(m.wp);
    JTJ.bottomRightCorner<3, 3>() = m.wppt.trace() * Eigen::Matrix3d::Identity() - m.wppt;
    JTr.head<3>() = m.wr;
    JTr.tail<3>() = m.wpxr;
    JTJ += m.wjjt;
    JTr += m.wje;
}

/// Gauss-Newton step; planar mode solves only for (x, y, yaw) = tangent indices 0, 1, 5.
Vector6d SolveStep(const Matrix6d& JTJ, const Vector6d& JTr, bool planar) {
    if (!planar) return JTJ.ldlt().solve(-JTr);
    const int dofs[3] = {0, 1, 5};
    Eigen::Matrix3d A;
    Eigen::Vector3d b;
    for (int i = 0; i < 3; ++i) {
        b[i] = -JTr[dofs[i]];
        for (int j = 0; j < 3; ++j) A(i, j) = JTJ(dofs[i], dofs[j]);
    }
    const Eigen::Vector3d x = A.ldlt().solve(b);
    Vector6d dx = Vector6d::Zero();
    for (int i = 0; i < 3; ++i) dx[dofs[i]] = x[i];
    return dx;
}

/// The robust cost the iterations decrease: every point without a correspondence costs the kernel's
/// ceiling k (so iterates with different correspondence counts compare).
double Cost(const Moments& m, bool planes_only, std::size_t points, double kernel) {
    const std::size_t used = planes_only ? m.plane_count : m.count;
    return (planes_only ? m.plane_cost : m.cost + m.plane_cost) + kernel * static_cast<double>(points - used);
}

Eigen::Isometry3d Translation(const Eigen::Vector3d& t) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.translation() = t;
    return T;
}

}  // namespace

IcpResult RegisterPointsToMap(const std::vector<Eigen::Vector3d>& points_in_sensor, const VoxelHashMap& map,
                              const Eigen::Isometry3d& T_initial, const IcpParams& params) {
    IcpResult result;
    result.T_world_sensor = T_initial;
    if (map.Empty() || points_in_sensor.empty()) return result;

    // Updates are applied in a frame centred at the initial sensor position; the fixed point is
    // the same as with world-origin updates (KISS-ICP), the steps are better conditioned far
    // from the origin.
    const Eigen::Vector3d centre = T_initial.translation();
    const Eigen::Isometry3d T_centred0 = Translation(-centre) * T_initial;
    Eigen::Isometry3d T_centred = T_centred0;
    Matrix6d JTJ;
    Vector6d JTr;
    result.valid = true;
    // Per source point, its map neighbourhood between iterations (the map is fixed during ICP); a
    // buffer of the calling thread, reused from scan to scan.
    static thread_local std::vector<VoxelHashMap::Neighbourhood> neighbourhoods;
    neighbourhoods.assign(points_in_sensor.size(), VoxelHashMap::Neighbourhood{});
    // Anderson acceleration in the coordinates y of T_centred = Exp(y) T_centred0. An extrapolated
    // iterate is kept only when its robust cost is no higher than the last kept iterate's; otherwise
    // the plain step from that iterate is taken. The stopping test is the plain step's, as without it.
    AndersonAccelerator anderson(params.anderson_depth);
    Vector6d y = Vector6d::Zero();
    Eigen::Isometry3d T_plain = T_centred0;  // the plain step's result from the last kept iterate
    bool extrapolated = false;
    double kept_cost = std::numeric_limits<double>::infinity();
    for (int iteration = 0; iteration < params.max_iterations; ++iteration) {
        const Eigen::Isometry3d T = Translation(centre) * T_centred;
        const Moments moments = Accumulate(points_in_sensor, map, T, centre, params, neighbourhoods);
        // Decided once per frame, from the initial guess: the iterations then minimize one cost.
        // Never in planar mode: a 2D scan has few points on lines (radish intel: ~60 per scan), and the
        // lines alone fell below min_correspondences on a third of its scans; mixed, they register.
        if (iteration == 0) result.planes_only = params.point_to_plane && !params.planar && PlanesSuffice(moments);
        result.correspondences = result.planes_only ? moments.plane_count : moments.count;
        result.plane_correspondences = moments.plane_count;
        result.iterations = iteration + 1;
        if (result.correspondences < static_cast<std::size_t>(std::max(params.min_correspondences, 1))) {
            result.valid = false;
            break;
        }
        if (params.anderson_depth > 0) {
            const double cost = Cost(moments, result.planes_only, points_in_sensor.size(), params.kernel);
            if (extrapolated && !(cost <= kept_cost)) {
                T_centred = T_plain;
                y = LogSE3(T_centred * T_centred0.inverse());
                extrapolated = false;
                anderson.Reset();
                continue;
            }
            kept_cost = cost;
        }
        AssembleNormalEquations(moments, result.planes_only, JTJ, JTr);
        const Vector6d dx = SolveStep(JTJ, JTr, params.planar);
        if (!dx.allFinite()) {
            result.valid = false;
            break;
        }
        T_centred = ExpSE3(dx) * T_centred;
        if (dx.norm() < params.convergence) {
            result.converged = true;
            break;
        }
        if (params.anderson_depth > 0) {
            T_plain = T_centred;
            y = anderson.Next(y, LogSE3(T_plain * T_centred0.inverse()), extrapolated);
            if (extrapolated) T_centred = ExpSE3(y) * T_centred0;
        }
    }
    if (!result.valid) {
        result.T_world_sensor = T_initial;
        return result;
    }
    result.T_world_sensor = Translation(centre) * T_centred;
    return result;
}

Eigen::Isometry3d ProjectToPlanar(const Eigen::Isometry3d& T) {
    const Eigen::Vector3d x_axis = T.linear().col(0);
    const double yaw = std::atan2(x_axis.y(), x_axis.x());
    Eigen::Isometry3d planar = Eigen::Isometry3d::Identity();
    planar.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    planar.translation() = Eigen::Vector3d(T.translation().x(), T.translation().y(), 0.0);
    return planar;
}

}  // namespace revisit
