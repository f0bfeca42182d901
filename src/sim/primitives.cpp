#include "sim/primitives.hpp"

#include <algorithm>
#include <cmath>

#include "sim/counter_random.hpp"

namespace revisit {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kTwoPi = 6.283185307179586;

/// Smooth value noise in [-1, 1]: random values on a unit lattice, blended with a smoothstep.
double ValueNoise(double x, double y, std::uint64_t seed) {
    auto lattice = [seed](std::int64_t i, std::int64_t j) {
        // Offset by SplitMix64's increment: the lattice values of the worlds measured in src/sim/README.md.
        const std::uint64_t key = seed ^ (static_cast<std::uint64_t>(i) * 0x9E3779B97F4A7C15ULL) ^
                                  (static_cast<std::uint64_t>(j) * 0xC2B2AE3D27D4EB4FULL);
        return 2.0 * UnitFromKey(key - 0x9E3779B97F4A7C15ULL) - 1.0;
    };
    const double fx = std::floor(x), fy = std::floor(y);
    const auto i = static_cast<std::int64_t>(fx), j = static_cast<std::int64_t>(fy);
    double u = x - fx, v = y - fy;
    u = u * u * (3.0 - 2.0 * u);
    v = v * v * (3.0 - 2.0 * v);
    return (lattice(i, j) * (1 - u) + lattice(i + 1, j) * u) * (1 - v) + (lattice(i, j + 1) * (1 - u) + lattice(i + 1, j + 1) * u) * v;
}

}  // namespace

float Reflectivity(Material material) {
    switch (material) {
        case Material::kGround: return 0.25f;
        case Material::kRoad: return 0.12f;
        case Material::kBuilding: return 0.35f;
        case Material::kGlass: return 0.05f;
        case Material::kVegetation: return 0.45f;
        case Material::kMetal: return 0.70f;
        case Material::kCar: return 0.55f;
        case Material::kWall: return 0.40f;
        case Material::kFurniture: return 0.30f;
    }
    return 0.3f;
}

double Ground::Height(double x, double y) const {
    const double k = kTwoPi / wavelength;
    double h = base_height + slope_x * x + slope_y * y + amplitude * std::sin(k * x) * std::cos(k * 0.7 * y);
    if (relief > 0.0) h += relief * ValueNoise(x / relief_wavelength, y / relief_wavelength, seed);
    return h;
}

double Ground::Roughness(double x, double y) const {
    if (roughness <= 0.0) return 0.0;
    // Two octaves: pebbles and cracks on top of a gentler waviness.
    const double s = 1.0 / roughness_wavelength;
    return roughness * (0.65 * ValueNoise(x * s, y * s, seed ^ 0x5151) + 0.35 * ValueNoise(2.7 * x * s, 2.7 * y * s, seed ^ 0x7373));
}

Eigen::Vector2d Ground::Gradient(double x, double y) const {
    const double k = kTwoPi / wavelength;
    Eigen::Vector2d g(slope_x + amplitude * k * std::cos(k * x) * std::cos(k * 0.7 * y),
                      slope_y - amplitude * 0.7 * k * std::sin(k * x) * std::sin(k * 0.7 * y));
    if (relief > 0.0) {  // central differences: the relief is only used where the raster does not reach
        const double e = 0.05 * relief_wavelength;
        const double r0 = relief * ValueNoise((x - e) / relief_wavelength, y / relief_wavelength, seed);
        const double r1 = relief * ValueNoise((x + e) / relief_wavelength, y / relief_wavelength, seed);
        const double r2 = relief * ValueNoise(x / relief_wavelength, (y - e) / relief_wavelength, seed);
        const double r3 = relief * ValueNoise(x / relief_wavelength, (y + e) / relief_wavelength, seed);
        g += Eigen::Vector2d(r1 - r0, r3 - r2) / (2.0 * e);
    }
    return g;
}

double IntersectBox(const OrientedBox& box, const Eigen::Vector3d& origin, const Eigen::Vector3d& direction,
                    double t_min, double t_max) {
    // Ray in the box frame: rotate XY by -yaw about the box centre.
    const double c = std::cos(box.yaw);
    const double s = std::sin(box.yaw);
    const double ox = origin.x() - box.center.x();
    const double oy = origin.y() - box.center.y();
    const double lx = c * ox + s * oy;
    const double ly = -s * ox + c * oy;
    const double dx = c * direction.x() + s * direction.y();
    const double dy = -s * direction.x() + c * direction.y();
    double t_enter = t_min;
    double t_exit = t_max;
    if (!Slab(lx, dx, -box.half_size.x(), box.half_size.x(), t_enter, t_exit)) return kInf;
    if (!Slab(ly, dy, -box.half_size.y(), box.half_size.y(), t_enter, t_exit)) return kInf;
    if (!Slab(origin.z(), direction.z(), box.z_min, box.z_max, t_enter, t_exit)) return kInf;
    // A ray starting inside sees nothing of this box (the sensor is never inside an object).
    return t_enter > t_min ? t_enter : kInf;
}

double IntersectCylinder(const Cylinder& cylinder, const Eigen::Vector3d& origin, const Eigen::Vector3d& direction,
                         double t_min, double t_max) {
    const double ox = origin.x() - cylinder.center.x();
    const double oy = origin.y() - cylinder.center.y();
    const double a = direction.x() * direction.x() + direction.y() * direction.y();
    if (a < 1e-12) return kInf;  // vertical ray: poles are thin, ignore caps
    const double b = ox * direction.x() + oy * direction.y();
    const double c = ox * ox + oy * oy - cylinder.radius * cylinder.radius;
    const double disc = b * b - a * c;
    if (disc < 0.0) return kInf;
    const double t = (-b - std::sqrt(disc)) / a;
    if (t <= t_min || t >= t_max) return kInf;
    const double z = origin.z() + t * direction.z();
    return (z >= cylinder.z_min && z <= cylinder.z_max) ? t : kInf;
}

double IntersectSphere(const Sphere& sphere, const Eigen::Vector3d& origin, const Eigen::Vector3d& direction,
                       double t_min, double t_max) {
    const Eigen::Vector3d o = origin - sphere.center;
    const double b = o.dot(direction);
    const double c = o.squaredNorm() - sphere.radius * sphere.radius;
    const double disc = b * b - c;
    if (disc < 0.0) return kInf;
    const double t = -b - std::sqrt(disc);
    return (t > t_min && t < t_max) ? t : kInf;
}

double IntersectGround(const Ground& ground, const Eigen::Vector3d& origin, const Eigen::Vector3d& direction,
                       double t_min, double t_max) {
    // f(t) = z(t) - h(x(t), y(t)); start from the local tangent plane, then Newton.
    auto f = [&](double t) {
        const Eigen::Vector3d p = origin + t * direction;
        return p.z() - ground.Height(p.x(), p.y());
    };
    const double f0 = f(0.0);
    if (f0 <= 0.0) return kInf;  // origin below ground
    double t = 0.0;
    for (int iteration = 0; iteration < 8; ++iteration) {
        const Eigen::Vector3d p = origin + t * direction;
        const Eigen::Vector2d g = ground.Gradient(p.x(), p.y());
        const double df = direction.z() - g.x() * direction.x() - g.y() * direction.y();
        if (df >= -1e-9) return kInf;  // moving away from (or parallel to) the local ground
        const double step = -f(t) / df;
        t += step;
        if (t > t_max * 1.5 || t < 0.0) return kInf;
        if (std::abs(step) < 1e-5) break;
    }
    if (std::abs(f(t)) > 1e-3) return kInf;
    return (t > t_min && t < t_max) ? t : kInf;
}

Eigen::Vector4d BoundsXY(const OrientedBox& box) {
    const double c = std::abs(std::cos(box.yaw));
    const double s = std::abs(std::sin(box.yaw));
    const double ex = c * box.half_size.x() + s * box.half_size.y();
    const double ey = s * box.half_size.x() + c * box.half_size.y();
    return {box.center.x() - ex, box.center.y() - ey, box.center.x() + ex, box.center.y() + ey};
}

Eigen::Vector4d BoundsXY(const Cylinder& cylinder) {
    const double r = cylinder.radius;
    return {cylinder.center.x() - r, cylinder.center.y() - r, cylinder.center.x() + r, cylinder.center.y() + r};
}

Eigen::Vector4d BoundsXY(const Sphere& sphere) {
    const double r = sphere.radius;
    return {sphere.center.x() - r, sphere.center.y() - r, sphere.center.x() + r, sphere.center.y() + r};
}

}  // namespace revisit
