#include "odometry/correlative_matcher.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

namespace revisit {
namespace {

/// Blocks of up to 8 x 8 cells at the coarsest level: coarser blocks in a building light up nearly
/// everywhere and bound nothing (measured: 7 levels cost 5x more on carmen_kitti's maps).
constexpr int kMaxLevels = 4;
constexpr std::size_t kMaxPoints = 800;  ///< scan points scored at most (every k-th beyond)
constexpr double kKeptShare = 0.8;       ///< far points are dropped only while this share remains

/// The likelihood grid and its max-pooled levels: level l, cell (i, j) = max of level 0 over
/// [i, i + 2^l) x [j, j + 2^l).
struct GridPyramid {
    int size = 0;  ///< cells per side
    double resolution = 0.0;
    Eigen::Vector2d origin = Eigen::Vector2d::Zero();  ///< [m] corner of cell (0, 0)
    std::vector<std::vector<std::uint8_t>> levels;

    std::uint8_t At(int level, int i, int j) const {
        if (i < 0 || j < 0 || i >= size || j >= size) return 0;
        return levels[static_cast<std::size_t>(level)][static_cast<std::size_t>(j) * static_cast<std::size_t>(size) + static_cast<std::size_t>(i)];
    }
};

/// Cells within which a reference point lights the grid: two sigmas.
int KernelCells(double sigma_cells) { return std::max(1, static_cast<int>(std::ceil(2.0 * sigma_cells))); }

void Rasterize(GridPyramid& grid, const std::vector<Eigen::Vector3d>& reference, double sigma_cells) {
    const int n = grid.size;
    auto& base = grid.levels[0];
    const double inv = 1.0 / grid.resolution;
    const int kernel_cells = KernelCells(sigma_cells);
    const double inv_var = 1.0 / (sigma_cells * sigma_cells);
    for (const auto& p : reference) {
        const double u = (p.x() - grid.origin.x()) * inv, v = (p.y() - grid.origin.y()) * inv;
        const int ci = static_cast<int>(std::floor(u)), cj = static_cast<int>(std::floor(v));
        if (ci < -kernel_cells || cj < -kernel_cells || ci >= n + kernel_cells || cj >= n + kernel_cells) continue;
        for (int j = std::max(0, cj - kernel_cells); j <= std::min(n - 1, cj + kernel_cells); ++j) {
            for (int i = std::max(0, ci - kernel_cells); i <= std::min(n - 1, ci + kernel_cells); ++i) {
                const double du = u - (i + 0.5), dv = v - (j + 0.5);
                const auto value = static_cast<std::uint8_t>(std::lround(255.0 * std::exp(-0.5 * (du * du + dv * dv) * inv_var)));
                auto& cell = base[static_cast<std::size_t>(j) * static_cast<std::size_t>(n) + static_cast<std::size_t>(i)];
                cell = std::max(cell, value);
            }
        }
    }
    for (std::size_t l = 1; l < grid.levels.size(); ++l) {
        const int h = 1 << (l - 1);
        const auto& prev = grid.levels[l - 1];
        auto& next = grid.levels[l];
        next.assign(prev.size(), 0);
        const auto at = [&](int i, int j) -> std::uint8_t {
            return i < n && j < n ? prev[static_cast<std::size_t>(j) * static_cast<std::size_t>(n) + static_cast<std::size_t>(i)] : 0;
        };
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i)
                next[static_cast<std::size_t>(j) * static_cast<std::size_t>(n) + static_cast<std::size_t>(i)] =
                    std::max({at(i, j), at(i + h, j), at(i, j + h), at(i + h, j + h)});
    }
}

struct Candidate {
    int angle = 0;  ///< index into the rotations, 0 = the initial guess's
    int dx = 0, dy = 0;  ///< [cells] lower corner of the block of translations
    double bound = 0.0;  ///< score bound minus the prior penalty at the block's nearest translation
};

/// Smallest |d| over the integers [lo, hi].
int MinAbs(int lo, int hi) { return lo > 0 ? lo : (hi < 0 ? -hi : 0); }

/// Squared distance from `p` to the ray from `o` along the unit vector `u`.
double RayDistance2(const Eigen::Vector2d& p, const Eigen::Vector2d& o, const Eigen::Vector2d& u) {
    const Eigen::Vector2d d = p - o;
    const double t = std::max(0.0, d.dot(u));
    return (d - t * u).squaredNorm();
}

/// Squared distance from the ray (o, u) to the box [lo, hi]: 0 when it crosses the box, else attained
/// at the ray's origin or at a corner of the box (two disjoint convex sets in the plane).
double RayBoxDistance2(const Eigen::Vector2d& o, const Eigen::Vector2d& u, const Eigen::Vector2d& lo, const Eigen::Vector2d& hi) {
    double t_min = 0.0, t_max = std::numeric_limits<double>::infinity();
    bool crosses = true;
    for (int k = 0; k < 2 && crosses; ++k) {
        if (std::abs(u[k]) < 1e-12) {
            crosses = o[k] >= lo[k] && o[k] <= hi[k];
            continue;
        }
        double t0 = (lo[k] - o[k]) / u[k], t1 = (hi[k] - o[k]) / u[k];
        if (t0 > t1) std::swap(t0, t1);
        t_min = std::max(t_min, t0);
        t_max = std::min(t_max, t1);
        crosses = t_min <= t_max;
    }
    if (crosses) return 0.0;
    const Eigen::Vector2d nearest = o.cwiseMax(lo).cwiseMin(hi);
    double best = (o - nearest).squaredNorm();
    for (const Eigen::Vector2d& corner : {lo, hi, Eigen::Vector2d(lo.x(), hi.y()), Eigen::Vector2d(hi.x(), lo.y())})
        best = std::min(best, RayDistance2(corner, o, u));
    return best;
}

}  // namespace

CorrelativeMatch MatchCorrelative2D(const std::vector<Eigen::Vector3d>& reference_in_world,
                                    const std::vector<Eigen::Vector3d>& points_in_sensor, const Eigen::Isometry3d& T_initial,
                                    const CorrelativeMatchConfig& config) {
    CorrelativeMatch match;
    match.T_world_sensor = T_initial;
    if (reference_in_world.empty() || points_in_sensor.empty() || !(config.resolution > 0.0) || !(config.kernel_sigma_cells > 0.0))
        return match;
    const int kernel_cells = KernelCells(config.kernel_sigma_cells);

    // Scan points (x, y), every k-th beyond the budget.
    const std::size_t stride = std::max<std::size_t>(1, (points_in_sensor.size() + kMaxPoints - 1) / kMaxPoints);
    std::vector<Eigen::Vector2d> points;
    double reach = 0.0;
    for (std::size_t i = 0; i < points_in_sensor.size(); i += stride) {
        const Eigen::Vector2d p = points_in_sensor[i].head<2>();
        if (!p.allFinite()) continue;
        points.push_back(p);
        reach = std::max(reach, p.norm());
    }
    if (points.empty()) return match;
    // Far returns would coarsen the cell for all: those beyond what the grid holds at the asked
    // resolution are dropped while at least kKeptShare of the points remain.
    const double fit = 0.5 * (config.max_grid_cells - 2 * (kernel_cells + 2)) * config.resolution - config.linear_window;
    const auto within = static_cast<std::size_t>(std::count_if(points.begin(), points.end(), [&](const Eigen::Vector2d& p) { return p.norm() <= fit; }));
    if (fit > 0.0 && within < points.size() && static_cast<double>(within) >= kKeptShare * static_cast<double>(points.size())) {
        points.erase(std::remove_if(points.begin(), points.end(), [&](const Eigen::Vector2d& p) { return p.norm() > fit; }), points.end());
        reach = 0.0;
        for (const auto& p : points) reach = std::max(reach, p.norm());
    }
    reach = std::max(reach, config.resolution);

    // The grid covers every point under every searched pose; its cell grows when that needs more
    // than max_grid_cells per side.
    const int margin = kernel_cells + 2;
    const double half = reach + config.linear_window;
    const double resolution = std::max(config.resolution, 2.0 * half / std::max(1, config.max_grid_cells - 2 * margin));
    GridPyramid grid;
    grid.resolution = resolution;
    grid.size = static_cast<int>(std::ceil(2.0 * half / resolution)) + 2 * margin;
    const Eigen::Vector2d centre = T_initial.translation().head<2>();
    grid.origin = centre - Eigen::Vector2d::Constant(0.5 * grid.size * resolution);
    const int window = std::max(1, static_cast<int>(std::ceil(config.linear_window / resolution)));  // [cells] each way
    int levels = 1;
    while (levels < kMaxLevels && (1 << (levels - 1)) < window) ++levels;
    grid.levels.assign(static_cast<std::size_t>(levels), {});
    grid.levels[0].assign(static_cast<std::size_t>(grid.size) * static_cast<std::size_t>(grid.size), 0);
    Rasterize(grid, reference_in_world, config.kernel_sigma_cells);

    // Rotations: a step that moves nine in ten points by at most a cell (Olson: the farthest point; the
    // ICP that follows refines the rest), within the budget.
    std::vector<double> ranges;
    for (const auto& p : points) ranges.push_back(p.norm());
    const auto p90 = ranges.begin() + static_cast<std::ptrdiff_t>(0.9 * static_cast<double>(ranges.size() - 1));
    std::nth_element(ranges.begin(), p90, ranges.end());
    double angle_step = resolution / std::max(*p90, resolution);
    int angles = static_cast<int>(std::ceil(config.angular_window / angle_step));
    const int max_each_way = static_cast<int>((std::max<std::size_t>(config.max_angles, 3) - 1) / 2);
    if (angles > max_each_way) {
        angles = max_each_way;
        angle_step = config.angular_window / angles;
    }
    const double yaw0 = std::atan2(T_initial.linear()(1, 0), T_initial.linear()(0, 0));
    // Per rotation, each point's cell under the initial translation.
    const std::size_t n = points.size();
    std::vector<int> cells(static_cast<std::size_t>(2 * angles + 1) * n * 2);
    for (int a = -angles; a <= angles; ++a) {
        const double yaw = yaw0 + a * angle_step, c = std::cos(yaw), s = std::sin(yaw);
        int* out = &cells[static_cast<std::size_t>(a + angles) * n * 2];
        for (std::size_t i = 0; i < n; ++i) {
            const Eigen::Vector2d q(c * points[i].x() - s * points[i].y() + centre.x(), s * points[i].x() + c * points[i].y() + centre.y());
            out[2 * i] = static_cast<int>(std::floor((q.x() - grid.origin.x()) / resolution));
            out[2 * i + 1] = static_cast<int>(std::floor((q.y() - grid.origin.y()) / resolution));
        }
    }
    const double full = 255.0 * static_cast<double>(n);
    const double penalty_scale = config.prior_weight * full;
    const double prior_cells = config.prior_distance > 0.0 ? config.prior_distance / resolution : static_cast<double>(window);
    // The heading ray in cells from the centre, its direction per rotation (the chord of the turn).
    const Eigen::Vector2d heading_origin = (config.heading_origin - centre) / resolution;
    std::vector<Eigen::Vector2d> chord(static_cast<std::size_t>(2 * angles + 1));
    for (int a = -angles; a <= angles; ++a) {
        const double turn = std::remainder(yaw0 + a * angle_step - config.heading_yaw, 2.0 * M_PI);
        const double heading = config.heading_yaw + 0.5 * turn;
        chord[static_cast<std::size_t>(a + angles)] = Eigen::Vector2d(std::cos(heading), std::sin(heading));
    }
    const double heading_scale = config.heading_prior ? config.prior_weight * full / (prior_cells * prior_cells) : 0.0;
    const auto bound = [&](int level, int angle, int dx, int dy) {
        const int* c = &cells[static_cast<std::size_t>(angle + angles) * n * 2];
        long sum = 0;
        for (std::size_t i = 0; i < n; ++i) sum += grid.At(level, c[2 * i] + dx, c[2 * i + 1] + dy);
        const int span = (1 << level) - 1;
        const double mx = MinAbs(dx, std::min(dx + span, window)), my = MinAbs(dy, std::min(dy + span, window));
        const double f = 0.5 * (mx * mx + my * my) / (prior_cells * prior_cells) +
                         (angles > 0 ? static_cast<double>(angle) * angle / (static_cast<double>(angles) * angles) : 0.0);
        double off_heading = 0.0;
        if (heading_scale > 0.0) {
            const Eigen::Vector2d lo(dx, dy), hi(std::min(dx + span, window), std::min(dy + span, window));
            off_heading = heading_scale * RayBoxDistance2(heading_origin, chord[static_cast<std::size_t>(angle + angles)], lo, hi);
        }
        return static_cast<double>(sum) - 0.5 * penalty_scale * f - off_heading;
    };
    const auto by_bound = [](const Candidate& a, const Candidate& b) {
        if (a.bound != b.bound) return a.bound > b.bound;
        if (std::abs(a.angle) != std::abs(b.angle)) return std::abs(a.angle) < std::abs(b.angle);
        if (a.angle != b.angle) return a.angle < b.angle;
        if (a.dx != b.dx) return a.dx < b.dx;
        return a.dy < b.dy;
    };

    // Coarsest level: every rotation, blocks of 2^top translations over the window.
    const int top = levels - 1, block = 1 << top;
    std::vector<Candidate> roots;
    for (int a = -angles; a <= angles; ++a)
        for (int dy = -window; dy <= window; dy += block)
            for (int dx = -window; dx <= window; dx += block) roots.push_back({a, dx, dy, bound(top, a, dx, dy)});
    std::sort(roots.begin(), roots.end(), by_bound);

    Candidate best{0, 0, 0, -std::numeric_limits<double>::infinity()};
    // Depth-first branch and bound: a block whose bound cannot beat the best finest score is dropped.
    struct Frame {
        std::vector<Candidate> children;
        std::size_t next = 0;
        int level = 0;
    };
    std::vector<Frame> stack;
    stack.push_back({std::move(roots), 0, top});
    while (!stack.empty()) {
        Frame& frame = stack.back();
        if (frame.next >= frame.children.size() || frame.children[frame.next].bound <= best.bound) {
            stack.pop_back();
            continue;
        }
        const Candidate c = frame.children[frame.next++];
        if (frame.level == 0) {
            best = c;
            continue;
        }
        const int level = frame.level - 1, step = 1 << level;
        std::vector<Candidate> children;
        for (int oy = 0; oy <= step; oy += step)
            for (int ox = 0; ox <= step; ox += step) {
                const int dx = c.dx + ox, dy = c.dy + oy;
                if (dx > window || dy > window) continue;
                children.push_back({c.angle, dx, dy, bound(level, c.angle, dx, dy)});
            }
        std::sort(children.begin(), children.end(), by_bound);
        stack.push_back({std::move(children), 0, level});
    }
    if (!std::isfinite(best.bound)) return match;

    const double yaw = yaw0 + best.angle * angle_step;
    match.T_world_sensor = Eigen::Isometry3d::Identity();
    match.T_world_sensor.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    match.T_world_sensor.translation() = Eigen::Vector3d(centre.x() + best.dx * resolution, centre.y() + best.dy * resolution, 0.0);
    long sum = 0;
    const int* c = &cells[static_cast<std::size_t>(best.angle + angles) * n * 2];
    for (std::size_t i = 0; i < n; ++i) sum += grid.At(0, c[2 * i] + best.dx, c[2 * i + 1] + best.dy);
    match.score = static_cast<double>(sum) / full;
    match.resolution = resolution;
    match.angle_step = angle_step;
    match.points = n;
    match.valid = true;
    match.at_linear_edge = std::abs(best.dx) >= window || std::abs(best.dy) >= window;
    match.at_angular_edge = angles > 0 && std::abs(best.angle) >= angles;
    match.at_edge = match.at_linear_edge || match.at_angular_edge;
    return match;
}

}  // namespace revisit
