#pragma once
/// Ray casting against a World, accelerated by a uniform 2D grid over the XY plane
/// (Amanatides-Woo traversal) with per-cell height bounds, so rays over low
/// cells and rays into the sky cost little.
#include <Eigen/Core>
#include <cstdint>
#include <limits>
#include <vector>

#include "sim/world.hpp"

namespace revisit {

struct RayCasterConfig {
    double cell_size = 4.0;            ///< [m] grid cell edge
    double road_mask_resolution = 1.0; ///< [m] raster of asphalt areas (intensity only)
};

struct RayHit {
    double range = std::numeric_limits<double>::infinity();  ///< [m] along the unit direction; inf = no return
    Material material = Material::kGround;
    bool hit() const { return range < std::numeric_limits<double>::infinity(); }
};

class RayCaster {
  public:
    /// Indexes the world's static content; `world` must outlive the caster.
    explicit RayCaster(const World& world, const RayCasterConfig& config = {});

    /// First hit along origin + t * direction (unit), t in (min_range, max_range). `time` [s]
    /// selects which parked cars exist; `dynamic_boxes` (moving cars now) are tested by brute force.
    /// `ray_key` seeds the ray's draws (depth in foliage, micro-relief is a function of the place).
    RayHit Cast(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction, double min_range,
                double max_range, double time, const std::vector<OrientedBox>& dynamic_boxes,
                std::uint64_t ray_key = 0) const;
    RayHit Cast(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction, double min_range,
                double max_range, double time = 0.0) const;

    const World& world() const { return world_; }

  private:
    enum : std::uint32_t { kBox = 0u, kCylinder = 1u << 30, kSphere = 2u << 30, kTypeMask = 3u << 30 };
    /// A box with its rotation precomputed (sin/cos dominated the cost of casting).
    struct PreparedBox {
        double cx, cy, c, s, hx, hy, z_min, z_max;
        float visible_from, visible_until;
        Material material;
    };
    bool IsRoad(double x, double y) const;
    double GroundHeight(double x, double y, Eigen::Vector2d* gradient) const;
    double IntersectGroundRaster(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction, double t_min,
                                 double t_max) const;
    double CastCell(std::size_t cell, const Eigen::Vector3d& origin, const Eigen::Vector3d& direction,
                    double t_min, double t_max, double time, std::uint64_t ray_key, Material& material) const;

    const World& world_;
    RayCasterConfig config_;
    Eigen::Vector2d origin_xy_;           ///< [m] corner of cell (0, 0)
    int nx_ = 0, ny_ = 0;
    std::vector<std::uint32_t> cell_begin_;  ///< CSR offsets into items_, size nx*ny+1
    std::vector<std::uint32_t> items_;       ///< type bits | primitive index
    std::vector<float> cell_top_;            ///< [m] highest z of anything in the cell
    std::vector<PreparedBox> boxes_;
    Eigen::Vector2d height_origin_;          ///< ground height raster (bilinear), same extent as the grid
    double height_resolution_ = 2.0;         ///< [m]
    double inverse_height_resolution_ = 0.5;
    int height_nx_ = 0, height_ny_ = 0;
    std::vector<double> heights_;
    double max_slope_ = 0.0;                 ///< [m per m] steepest ground gradient on the raster
    Eigen::Vector2d road_origin_;
    int road_nx_ = 0, road_ny_ = 0;
    std::vector<std::uint8_t> road_mask_;
};

}  // namespace revisit
