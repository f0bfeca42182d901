#pragma once
/// Geometric primitives of a simulated world and their exact ray intersections.
/// Everything a street scene needs is a union of vertical prisms (oriented boxes),
/// vertical cylinders (poles, trunks) and spheres (tree crowns); the ground is a height field.
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

namespace revisit {

/// Slab test of one axis (Kay-Kajiya): narrows [t_enter, t_exit] to where the ray is between lo and hi;
/// false when the interval becomes empty or the ray is parallel and outside. Inline: the ray caster's hot loop.
inline bool Slab(double origin, double direction, double lo, double hi, double& t_enter, double& t_exit) {
    if (std::abs(direction) < 1e-12) return origin >= lo && origin <= hi;
    const double inv = 1.0 / direction;
    double t0 = (lo - origin) * inv;
    double t1 = (hi - origin) * inv;
    if (t0 > t1) std::swap(t0, t1);
    t_enter = std::max(t_enter, t0);
    t_exit = std::min(t_exit, t1);
    return t_enter <= t_exit;
}

/// Surface type: sets the simulated reflectivity (intensity) of a hit.
enum class Material : std::uint8_t { kGround, kRoad, kBuilding, kGlass, kVegetation, kMetal, kCar, kWall, kFurniture };

/// Diffuse reflectivity of a material [0..1], used by the intensity model.
float Reflectivity(Material material);

/// Box with vertical sides, rotated by `yaw` about z: the building block of buildings, cars, walls.
struct OrientedBox {
    Eigen::Vector2d center = Eigen::Vector2d::Zero();  ///< [m] in the world XY plane
    Eigen::Vector2d half_size{0.5, 0.5};               ///< [m] half extents along the box's own x and y
    double yaw = 0.0;                                  ///< [rad] rotation of the box x axis from world x
    double z_min = 0.0;                                ///< [m]
    double z_max = 1.0;                                ///< [m]
    Material material = Material::kBuilding;
    float visible_from = -std::numeric_limits<float>::infinity();  ///< [s] object exists from this time
    float visible_until = std::numeric_limits<float>::infinity();  ///< [s] and until this time
};

/// Vertical cylinder: poles, lamp posts, tree trunks.
struct Cylinder {
    Eigen::Vector2d center = Eigen::Vector2d::Zero();  ///< [m]
    double radius = 0.1;                               ///< [m]
    double z_min = 0.0;                                ///< [m]
    double z_max = 5.0;                                ///< [m]
    Material material = Material::kMetal;
};

/// Sphere: tree crowns, lamp heads.
struct Sphere {
    Eigen::Vector3d center = Eigen::Vector3d::Zero();  ///< [m]
    double radius = 1.0;                               ///< [m]
    Material material = Material::kVegetation;
};

/// Ground height field: a tilted plane plus a long-wavelength undulation (gentle slopes), metre-scale
/// relief (value noise: the slope varies from place to place as on a real street) and centimetre-scale
/// roughness. The roughness is only added where a ray hits (RayCaster), not to `Height`.
struct Ground {
    double base_height = 0.0;   ///< [m]
    double slope_x = 0.0;       ///< [m per m]
    double slope_y = 0.0;       ///< [m per m]
    double amplitude = 0.0;     ///< [m] of the undulation
    double wavelength = 300.0;  ///< [m] of the undulation
    double relief = 0.0;        ///< [m] amplitude of the metre-scale relief
    double relief_wavelength = 8.0;       ///< [m] its lattice spacing
    double roughness = 0.0;     ///< [m] amplitude of the centimetre-scale roughness
    double roughness_wavelength = 0.3;    ///< [m] its lattice spacing
    std::uint64_t seed = 0;     ///< of the relief and roughness

    double Height(double x, double y) const;
    /// Roughness at (x, y) [m], in [-roughness, roughness].
    double Roughness(double x, double y) const;
    /// d(height)/dx, d(height)/dy.
    Eigen::Vector2d Gradient(double x, double y) const;
};

/// Ray parameters are distances along a unit direction [m]. Each function returns
/// the entry distance in (t_min, t_max), or +infinity when the ray misses.
double IntersectBox(const OrientedBox& box, const Eigen::Vector3d& origin, const Eigen::Vector3d& direction,
                    double t_min, double t_max);
double IntersectCylinder(const Cylinder& cylinder, const Eigen::Vector3d& origin, const Eigen::Vector3d& direction,
                         double t_min, double t_max);
double IntersectSphere(const Sphere& sphere, const Eigen::Vector3d& origin, const Eigen::Vector3d& direction,
                       double t_min, double t_max);
/// First crossing of the ground: plane solution refined by Newton on the undulation.
double IntersectGround(const Ground& ground, const Eigen::Vector3d& origin, const Eigen::Vector3d& direction,
                       double t_min, double t_max);

/// Axis-aligned XY bounds of a primitive [m]: min x, min y, max x, max y.
Eigen::Vector4d BoundsXY(const OrientedBox& box);
Eigen::Vector4d BoundsXY(const Cylinder& cylinder);
Eigen::Vector4d BoundsXY(const Sphere& sphere);

}  // namespace revisit
