#include "sim/ray_caster.hpp"

#include <algorithm>
#include <cmath>

#include "sim/counter_random.hpp"

namespace revisit {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

/// Uniform in (0, 1] from a key (counter-based, like the scan simulator's draws).
double UnitDraw(std::uint64_t key) { return UnitFromKey(key) + 1.0 / 9007199254740992.0; }

/// A foliage volume: the return comes from an exponentially distributed depth after entering the
/// sphere (mean `free_path`), or the ray passes through when that depth is beyond the exit.
double IntersectFoliage(const Sphere& sphere, const Eigen::Vector3d& origin, const Eigen::Vector3d& direction,
                        double t_min, double t_max, double free_path, std::uint64_t key) {
    const Eigen::Vector3d o = origin - sphere.center;
    const double b = o.dot(direction);
    const double disc = b * b - (o.squaredNorm() - sphere.radius * sphere.radius);
    if (disc < 0.0) return kInf;
    const double root = std::sqrt(disc);
    const double t = std::max(-b - root, t_min) - free_path * std::log(UnitDraw(key));
    return (t > t_min && t < t_max && t < -b + root) ? t : kInf;
}

}  // namespace

RayCaster::RayCaster(const World& world, const RayCasterConfig& config) : world_(world), config_(config) {
    // Bounds of everything static, plus a margin so edge rays start inside.
    Eigen::Vector4d bounds(kInf, kInf, -kInf, -kInf);
    auto grow = [&](const Eigen::Vector4d& b) {
        bounds.head<2>() = bounds.head<2>().cwiseMin(b.head<2>());
        bounds.tail<2>() = bounds.tail<2>().cwiseMax(b.tail<2>());
    };
    for (const auto& box : world.boxes) grow(BoundsXY(box));
    for (const auto& cylinder : world.cylinders) grow(BoundsXY(cylinder));
    for (const auto& sphere : world.spheres) grow(BoundsXY(sphere));
    if (!std::isfinite(bounds.x())) bounds = Eigen::Vector4d(-1.0, -1.0, 1.0, 1.0);
    const double cell = config_.cell_size;
    origin_xy_ = bounds.head<2>() - Eigen::Vector2d::Constant(cell);
    nx_ = static_cast<int>(std::ceil((bounds.z() - origin_xy_.x()) / cell)) + 1;
    ny_ = static_cast<int>(std::ceil((bounds.w() - origin_xy_.y()) / cell)) + 1;
    const std::size_t num_cells = static_cast<std::size_t>(nx_) * ny_;

    // Two passes (count, fill) into a compressed row layout.
    std::vector<std::uint32_t> counts(num_cells + 1, 0);
    cell_top_.assign(num_cells, -std::numeric_limits<float>::infinity());
    auto for_cells = [&](const Eigen::Vector4d& b, double top, auto&& visit) {
        const int x0 = std::max(0, static_cast<int>((b.x() - origin_xy_.x()) / cell));
        const int y0 = std::max(0, static_cast<int>((b.y() - origin_xy_.y()) / cell));
        const int x1 = std::min(nx_ - 1, static_cast<int>((b.z() - origin_xy_.x()) / cell));
        const int y1 = std::min(ny_ - 1, static_cast<int>((b.w() - origin_xy_.y()) / cell));
        for (int y = y0; y <= y1; ++y)
            for (int x = x0; x <= x1; ++x) {
                const std::size_t c = static_cast<std::size_t>(y) * nx_ + x;
                cell_top_[c] = std::max(cell_top_[c], static_cast<float>(top));
                visit(c);
            }
    };
    auto all = [&](auto&& visit) {
        for (std::uint32_t i = 0; i < world.boxes.size(); ++i)
            for_cells(BoundsXY(world.boxes[i]), world.boxes[i].z_max, [&](std::size_t c) { visit(c, kBox | i); });
        for (std::uint32_t i = 0; i < world.cylinders.size(); ++i)
            for_cells(BoundsXY(world.cylinders[i]), world.cylinders[i].z_max,
                      [&](std::size_t c) { visit(c, kCylinder | i); });
        for (std::uint32_t i = 0; i < world.spheres.size(); ++i)
            for_cells(BoundsXY(world.spheres[i]), world.spheres[i].center.z() + world.spheres[i].radius,
                      [&](std::size_t c) { visit(c, kSphere | i); });
    };
    all([&](std::size_t c, std::uint32_t) { ++counts[c + 1]; });
    for (std::size_t c = 0; c < num_cells; ++c) counts[c + 1] += counts[c];
    cell_begin_ = counts;
    items_.resize(counts[num_cells]);
    all([&](std::size_t c, std::uint32_t item) { items_[counts[c]++] = item; });

    boxes_.reserve(world.boxes.size());
    for (const auto& b : world.boxes)
        boxes_.push_back({b.center.x(), b.center.y(), std::cos(b.yaw), std::sin(b.yaw), b.half_size.x(), b.half_size.y(),
                          b.z_min, b.z_max, b.visible_from, b.visible_until, b.material});
    // Ground heights on a raster: bilinear interpolation is within a millimetre of the smooth field.
    height_origin_ = origin_xy_;
    inverse_height_resolution_ = 1.0 / height_resolution_;
    height_nx_ = static_cast<int>(nx_ * cell / height_resolution_) + 2;
    height_ny_ = static_cast<int>(ny_ * cell / height_resolution_) + 2;
    heights_.resize(static_cast<std::size_t>(height_nx_) * height_ny_);
    for (int y = 0; y < height_ny_; ++y)
        for (int x = 0; x < height_nx_; ++x)
            heights_[static_cast<std::size_t>(y) * height_nx_ + x] =
                world.ground.Height(height_origin_.x() + x * height_resolution_, height_origin_.y() + y * height_resolution_);

    for (int y = 0; y + 1 < height_ny_; ++y)
        for (int x = 0; x + 1 < height_nx_; ++x) {
            const double h = heights_[static_cast<std::size_t>(y) * height_nx_ + x];
            max_slope_ = std::max({max_slope_, std::abs(heights_[static_cast<std::size_t>(y) * height_nx_ + x + 1] - h),
                                   std::abs(heights_[static_cast<std::size_t>(y + 1) * height_nx_ + x] - h)});
        }
    max_slope_ = max_slope_ * 1.5 / height_resolution_ + 1e-6;  // diagonal and safety margin

    // Asphalt raster for the intensity model.
    const double res = config_.road_mask_resolution;
    road_origin_ = origin_xy_;
    road_nx_ = static_cast<int>(nx_ * cell / res) + 1;
    road_ny_ = static_cast<int>(ny_ * cell / res) + 1;
    road_mask_.assign(static_cast<std::size_t>(road_nx_) * road_ny_, 0);
    for (const auto& road : world.roads) {
        const Eigen::Vector2d lo = road.a.cwiseMin(road.b) - Eigen::Vector2d::Constant(road.half_width);
        const Eigen::Vector2d hi = road.a.cwiseMax(road.b) + Eigen::Vector2d::Constant(road.half_width);
        const Eigen::Vector2d ab = road.b - road.a;
        const double len2 = std::max(ab.squaredNorm(), 1e-12);
        for (int y = std::max(0, int((lo.y() - road_origin_.y()) / res)); y < std::min(road_ny_, int((hi.y() - road_origin_.y()) / res) + 1); ++y)
            for (int x = std::max(0, int((lo.x() - road_origin_.x()) / res)); x < std::min(road_nx_, int((hi.x() - road_origin_.x()) / res) + 1); ++x) {
                const Eigen::Vector2d p = road_origin_ + Eigen::Vector2d(x + 0.5, y + 0.5) * res;
                const double u = std::clamp((p - road.a).dot(ab) / len2, 0.0, 1.0);
                if ((p - road.a - u * ab).norm() <= road.half_width) road_mask_[static_cast<std::size_t>(y) * road_nx_ + x] = 1;
            }
    }
}

bool RayCaster::IsRoad(double x, double y) const {
    const int ix = static_cast<int>((x - road_origin_.x()) / config_.road_mask_resolution);
    const int iy = static_cast<int>((y - road_origin_.y()) / config_.road_mask_resolution);
    if (ix < 0 || iy < 0 || ix >= road_nx_ || iy >= road_ny_) return false;
    return road_mask_[static_cast<std::size_t>(iy) * road_nx_ + ix] != 0;
}

double RayCaster::GroundHeight(double x, double y, Eigen::Vector2d* gradient) const {
    const double fx = (x - height_origin_.x()) * inverse_height_resolution_;
    const double fy = (y - height_origin_.y()) * inverse_height_resolution_;
    const int ix = static_cast<int>(fx), iy = static_cast<int>(fy);  // truncation = floor where it matters
    if (fx < 0.0 || fy < 0.0 || ix + 1 >= height_nx_ || iy + 1 >= height_ny_) {
        if (gradient) *gradient = world_.ground.Gradient(x, y);
        return world_.ground.Height(x, y);
    }
    const double u = fx - ix, v = fy - iy;
    const double* row0 = &heights_[static_cast<std::size_t>(iy) * height_nx_ + ix];
    const double* row1 = row0 + height_nx_;
    const double h00 = row0[0], h10 = row0[1], h01 = row1[0], h11 = row1[1];
    if (gradient)
        *gradient = Eigen::Vector2d(((h10 - h00) * (1 - v) + (h11 - h01) * v) * inverse_height_resolution_,
                                    ((h01 - h00) * (1 - u) + (h11 - h10) * u) * inverse_height_resolution_);
    return (h00 * (1 - u) + h10 * u) * (1 - v) + (h01 * (1 - u) + h11 * u) * v;
}

double RayCaster::IntersectGroundRaster(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction, double t_min,
                                        double t_max) const {
    // Newton on f(t) = z(t) - h(x(t), y(t)) from the sensor, as IntersectGround but on the raster.
    // The ground rises at most max_slope_ per horizontal metre: steeper rays never come down to it.
    if (direction.z() >= max_slope_ * direction.head<2>().norm()) return kInf;
    double t = 0.0;
    for (int iteration = 0; iteration < 10; ++iteration) {
        const Eigen::Vector3d p = origin + t * direction;
        Eigen::Vector2d g;
        const double f = p.z() - GroundHeight(p.x(), p.y(), &g);
        if (iteration == 0 && f <= 0.0) return kInf;  // origin below the ground
        const double df = direction.z() - g.x() * direction.x() - g.y() * direction.y();
        if (df >= -1e-9) return kInf;
        const double step = -f / df;
        t += step;
        if (t > t_max * 1.5 || t < 0.0) return kInf;
        if (std::abs(step) < 1e-3) return (t > t_min && t < t_max) ? t : kInf;
    }
    return kInf;
}

double RayCaster::CastCell(std::size_t cell, const Eigen::Vector3d& origin, const Eigen::Vector3d& direction,
                           double t_min, double t_max, double time, std::uint64_t ray_key,
                           Material& material) const {
    double best = t_max;
    for (std::uint32_t k = cell_begin_[cell]; k < cell_begin_[cell + 1]; ++k) {
        const std::uint32_t item = items_[k];
        const std::uint32_t index = item & ~kTypeMask;
        double t = kInf;
        switch (item & kTypeMask) {
            case kBox: {
                const PreparedBox& b = boxes_[index];
                if (time < b.visible_from || time > b.visible_until) continue;
                // IntersectBox with the rotation precomputed.
                const double ox = origin.x() - b.cx, oy = origin.y() - b.cy;
                double t_enter = t_min, t_exit = best;
                if (!Slab(b.c * ox + b.s * oy, b.c * direction.x() + b.s * direction.y(), -b.hx, b.hx, t_enter, t_exit) ||
                    !Slab(-b.s * ox + b.c * oy, -b.s * direction.x() + b.c * direction.y(), -b.hy, b.hy, t_enter, t_exit) ||
                    !Slab(origin.z(), direction.z(), b.z_min, b.z_max, t_enter, t_exit) || t_enter <= t_min)
                    continue;
                t = t_enter;
                if (t < best) material = b.material;
                break;
            }
            case kCylinder:
                t = IntersectCylinder(world_.cylinders[index], origin, direction, t_min, best);
                if (t < best) material = world_.cylinders[index].material;
                break;
            default: {
                const Sphere& sphere = world_.spheres[index];
                t = sphere.material == Material::kVegetation && world_.foliage_free_path > 0.0
                        ? IntersectFoliage(sphere, origin, direction, t_min, best, world_.foliage_free_path,
                                           ray_key ^ (index * 0xD1B54A32D192ED03ULL))
                        : IntersectSphere(sphere, origin, direction, t_min, best);
                if (t < best) material = sphere.material;
                break;
            }
        }
        if (t < best) best = t;
    }
    return best;
}

RayHit RayCaster::Cast(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction, double min_range,
                       double max_range, double time) const {
    static const std::vector<OrientedBox> kNone;
    return Cast(origin, direction, min_range, max_range, time, kNone);
}

RayHit RayCaster::Cast(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction, double min_range,
                       double max_range, double time, const std::vector<OrientedBox>& dynamic_boxes,
                       std::uint64_t ray_key) const {
    RayHit hit;
    Material material = Material::kGround;
    // Ground and ceiling bound the traversal; when nothing is in front of them they are the hit.
    double t_end = max_range;
    const double t_ground = IntersectGroundRaster(origin, direction, min_range, max_range);
    bool surface_at_end = t_ground < t_end;
    if (surface_at_end) t_end = t_ground;
    if (world_.has_ceiling && direction.z() > 1e-9) {
        const double t_ceiling = (world_.ceiling_height - origin.z()) / direction.z();
        if (t_ceiling > min_range && t_ceiling < t_end) {
            t_end = t_ceiling;
            surface_at_end = true;
            material = Material::kWall;
        }
    }
    double best = t_end;
    for (const auto& box : dynamic_boxes) {
        const double t = IntersectBox(box, origin, direction, min_range, best);
        if (t < best) best = t, material = box.material;
    }

    // 2D DDA over the cells the ray crosses between min_range and best.
    const double cell = config_.cell_size;
    double t0 = min_range;
    double t1 = best;
    // Clip to the grid rectangle.
    const Eigen::Vector2d lo = origin_xy_;
    const Eigen::Vector2d hi = origin_xy_ + Eigen::Vector2d(nx_, ny_) * cell;
    for (int a = 0; a < 2; ++a) {
        if (std::abs(direction[a]) < 1e-12) {
            if (origin[a] < lo[a] || origin[a] > hi[a]) t1 = -1.0;
            continue;
        }
        double ta = (lo[a] - origin[a]) / direction[a];
        double tb = (hi[a] - origin[a]) / direction[a];
        if (ta > tb) std::swap(ta, tb);
        t0 = std::max(t0, ta);
        t1 = std::min(t1, tb);
    }
    if (t0 < t1) {
        const Eigen::Vector2d start = origin.head<2>() + (t0 + 1e-9) * direction.head<2>();
        int ix = std::clamp(static_cast<int>((start.x() - lo.x()) / cell), 0, nx_ - 1);
        int iy = std::clamp(static_cast<int>((start.y() - lo.y()) / cell), 0, ny_ - 1);
        const int step_x = direction.x() >= 0.0 ? 1 : -1;
        const int step_y = direction.y() >= 0.0 ? 1 : -1;
        auto next_boundary = [&](int a, int i, int step) {
            if (std::abs(direction[a]) < 1e-12) return kInf;
            const double edge = lo[a] + (i + (step > 0 ? 1 : 0)) * cell;
            return (edge - origin[a]) / direction[a];
        };
        double t_next_x = next_boundary(0, ix, step_x);
        double t_next_y = next_boundary(1, iy, step_y);
        const double dt_x = std::abs(direction.x()) < 1e-12 ? kInf : cell / std::abs(direction.x());
        const double dt_y = std::abs(direction.y()) < 1e-12 ? kInf : cell / std::abs(direction.y());
        double t_cell_start = t0;
        while (true) {
            const double t_cell_end = std::min({t_next_x, t_next_y, t1});
            const std::size_t c = static_cast<std::size_t>(iy) * nx_ + ix;
            // Skip the cell when the ray passes above everything in it.
            const double z_low = origin.z() + direction.z() * (direction.z() >= 0.0 ? t_cell_start : t_cell_end);
            if (cell_begin_[c] != cell_begin_[c + 1] && z_low <= cell_top_[c]) {
                const double t = CastCell(c, origin, direction, min_range, best, time, ray_key, material);
                if (t < best) best = t, surface_at_end = false;
            }
            if (best <= t_cell_end || t_cell_end >= t1) break;
            t_cell_start = t_cell_end;
            if (t_next_x < t_next_y) {
                ix += step_x;
                t_next_x += dt_x;
            } else {
                iy += step_y;
                t_next_y += dt_y;
            }
            if (ix < 0 || iy < 0 || ix >= nx_ || iy >= ny_) break;
        }
    }
    if (best < t_end || surface_at_end) {
        hit.range = best;
        if (best == t_ground) {  // nothing in front of the ground: asphalt or not
            Eigen::Vector3d p = origin + best * direction;
            // Centimetre roughness: one Newton step from the smooth surface to the rough one (grazing
            // rays move most, as on a real street); bounded so a grazing ray cannot jump far.
            const double bump = world_.ground.Roughness(p.x(), p.y());
            if (bump != 0.0) {
                Eigen::Vector2d g;
                GroundHeight(p.x(), p.y(), &g);
                const double df = direction.z() - g.dot(direction.head<2>());
                if (df < -1e-3) hit.range = best + std::clamp(bump / df, -1.0, 1.0);
                p = origin + hit.range * direction;
            }
            material = IsRoad(p.x(), p.y()) ? Material::kRoad : Material::kGround;
        }
        hit.material = material;
    }
    return hit;
}

}  // namespace revisit
