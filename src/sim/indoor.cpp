#include <cmath>
#include <random>

#include "sim/generators.hpp"
#include "sim/objects.hpp"

namespace revisit {
namespace {

double Uniform(std::mt19937& rng, double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng); }

/// Wall from a to b with an optional door gap at a random place.
void WallWithDoor(const Eigen::Vector2d& a, const Eigen::Vector2d& b, bool door, const IndoorConfig& config,
                  std::mt19937& rng, World& world) {
    const double length = (b - a).norm();
    const Eigen::Vector2d along = (b - a) / length;
    if (!door || length < config.door_width + 1.0) {
        AddWall(a, b, 0.15, 0.0, config.wall_height, Material::kWall, world);
        return;
    }
    const double u = Uniform(rng, 0.5, length - config.door_width - 0.5);
    AddWall(a, a + along * u, 0.15, 0.0, config.wall_height, Material::kWall, world);
    AddWall(a + along * (u + config.door_width), b, 0.15, 0.0, config.wall_height, Material::kWall, world);
}

}  // namespace

World GenerateIndoor(const IndoorConfig& config, std::uint64_t seed) {
    std::mt19937 rng(static_cast<std::uint32_t>(seed * 3266489917u + 11u));
    World world;
    world.kind = "indoor";
    world.has_ceiling = config.ceiling;
    world.ceiling_height = config.wall_height;
    world.lane_offset = 0.0;
    const double size = config.room_size;
    const double half = config.corridor_half_width;
    const int nx = config.rooms_x + 1, ny = config.rooms_y + 1;
    StreetGraph& graph = world.streets;
    for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i) graph.nodes.emplace_back(i * size, j * size);
    for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i) {
            if (i + 1 < nx) graph.AddEdge(j * nx + i, j * nx + i + 1);
            if (j + 1 < ny) graph.AddEdge(j * nx + i, (j + 1) * nx + i);
        }
    // Rooms between the corridors: four walls, most with a door, furniture inside.
    for (int j = 0; j + 1 < ny; ++j)
        for (int i = 0; i + 1 < nx; ++i) {
            const Eigen::Vector2d lo(i * size + half, j * size + half), hi((i + 1) * size - half, (j + 1) * size - half);
            const Eigen::Vector2d c[4] = {lo, {hi.x(), lo.y()}, hi, {lo.x(), hi.y()}};
            for (int k = 0; k < 4; ++k) WallWithDoor(c[k], c[(k + 1) % 4], Uniform(rng, 0, 1) < 0.6, config, rng, world);
            for (int f = 0; f < config.furniture_per_room; ++f) {
                const Eigen::Vector2d half_size(Uniform(rng, 0.3, 1.0), Uniform(rng, 0.3, 0.8));
                const Eigen::Vector2d centre(Uniform(rng, lo.x() + 1.0, hi.x() - 1.0), Uniform(rng, lo.y() + 1.0, hi.y() - 1.0));
                const bool tall = Uniform(rng, 0, 1) < 0.3;
                AddStandingBox(centre, Uniform(rng, 0, 3.14159), half_size, 0.0, tall ? Uniform(rng, 1.6, 2.2) : 0.75,
                               Material::kFurniture, world);
            }
        }
    // Outer walls just beyond the outermost corridors.
    const Eigen::Vector2d lo(-half - 0.1, -half - 0.1), hi((nx - 1) * size + half + 0.1, (ny - 1) * size + half + 0.1);
    const Eigen::Vector2d c[4] = {lo, {hi.x(), lo.y()}, hi, {lo.x(), hi.y()}};
    for (int k = 0; k < 4; ++k) AddWall(c[k], c[(k + 1) % 4], 0.2, 0.0, config.wall_height, Material::kWall, world);
    // Pillars and cabinets along the corridors make them less self-similar.
    for (const auto& edge : graph.edges)
        if (Uniform(rng, 0, 1) < 0.3) {
            const Eigen::Vector2d p = PolylinePoint(OffsetPolyline(edge.polyline, half - 0.3), Uniform(rng, 2.0, edge.length - 2.0));
            AddStandingBox(p, 0.0, Eigen::Vector2d(0.2, 0.2), 0.0, config.wall_height, Material::kWall, world);
        }
    return world;
}

}  // namespace revisit
