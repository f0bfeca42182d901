#include <cmath>
#include <random>

#include "sim/generators.hpp"
#include "sim/objects.hpp"

namespace revisit {
namespace {

constexpr double kPi = 3.14159265358979323846;
double Uniform(std::mt19937& rng, double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng); }

/// One side of a road's verge (`side` -1 left, +1 right) between arc lengths s0 and s1: sections of
/// earth banks or cuttings whose height changes every 10 m (terraced, as boxes), and belts of trees with
/// gaps. A rail, posts and lamps repeat along a road; a real verge does not, and that pins the motion
/// along the road (KITTI 01, a highway, registers).
void AddVerge(const std::vector<Eigen::Vector2d>& line, double s0, double s1, int side, const HighwayConfig& config,
              std::mt19937& rng, World& world) {
    const double edge = config.road_half_width + 1.0;  // the guard rail
    for (double s = s0; s < s1;) {
        const double section = std::min(Uniform(rng, 30.0, 120.0), s1 - s);
        if (Uniform(rng, 0, 1) < config.bank_probability) {
            const double offset = edge + Uniform(rng, 3.0, 9.0);
            const double height = config.bank_height * Uniform(rng, 0.4, 1.6);
            for (double a = s; a < s + section - 1.0; a += 10.0) {
                const double b = std::min(a + 10.0, s + section);
                const double h = height * Uniform(rng, 0.7, 1.3);
                // Three terraces rising away from the road: a slope of about 1:2.
                for (int step = 0; step < 3; ++step) {
                    const auto foot = OffsetPolyline(line, side * (offset + 1.5 * h / 3.0 * step + 0.75 * h / 3.0));
                    AddWall(PolylinePoint(foot, a), PolylinePoint(foot, b), 1.5 * h / 3.0, -0.5, h * (step + 1) / 3.0,
                            Material::kGround, world);
                }
            }
        }
        if (Uniform(rng, 0, 1) < config.tree_belt_probability)
            for (double a = s + Uniform(rng, 0, 5); a < s + section; a += Uniform(rng, 4.0, 10.0))
                AddTree(PolylinePoint(OffsetPolyline(line, side * (edge + Uniform(rng, 5.0, 22.0))), a), rng, world);
        s += section;
    }
}

}  // namespace

World GenerateHighway(const HighwayConfig& config, std::uint64_t seed) {
    std::mt19937 rng(static_cast<std::uint32_t>(seed * 2246822519u + 5u));
    World world;
    world.kind = "highway";
    world.ground.amplitude = config.ground_amplitude;
    world.ground.wavelength = 900.0;
    world.lane_offset = 0.5 * config.road_half_width;
    world.ground.relief = config.ground_relief;
    world.ground.roughness = config.ground_roughness;
    world.ground.seed = seed * 0x9E3779B97F4A7C15ULL + 0xBB67AE85ULL;
    world.foliage_free_path = config.foliage_free_path;
    // A wobbly ring (sum of low harmonics), four ring nodes joined by two cross roads through a centre node.
    const double a2 = Uniform(rng, -1.0, 1.0), a3 = Uniform(rng, -1.0, 1.0), p2 = Uniform(rng, 0, 2 * kPi),
                 p3 = Uniform(rng, 0, 2 * kPi);
    auto ring = [&](double theta) {
        const double r = config.ring_radius *
                         (1.0 + config.radius_variation * (0.6 * a2 * std::sin(2 * theta + p2) + 0.4 * a3 * std::sin(3 * theta + p3)));
        return Eigen::Vector2d(r * std::cos(theta), r * std::sin(theta));
    };
    StreetGraph& graph = world.streets;
    const int ring_nodes = 8;
    for (int k = 0; k < ring_nodes; ++k) graph.nodes.push_back(ring(2 * kPi * k / ring_nodes));
    graph.nodes.push_back(Eigen::Vector2d::Zero());
    const int centre = ring_nodes;
    for (int k = 0; k < ring_nodes; ++k) {
        std::vector<Eigen::Vector2d> polyline;
        for (int i = 0; i <= 40; ++i) polyline.push_back(ring(2 * kPi * (k + i / 40.0) / ring_nodes));
        graph.AddEdge(k, (k + 1) % ring_nodes, polyline);
    }
    for (int k = 0; k < ring_nodes; k += 2) graph.AddEdge(k, centre);

    std::mt19937 clutter_rng(static_cast<std::uint32_t>(seed * 40503u + 202u));
    std::mt19937 verge_rng(static_cast<std::uint32_t>(seed * 69069u + 303u));  // own stream: the layout above stays
    for (const auto& edge : graph.edges) {
        const double length = edge.length;
        const double clear = 40.0;  // junctions stay open
        for (int side = -1; side <= 1; side += 2) {
            const auto rail = OffsetPolyline(edge.polyline, side * (config.road_half_width + 1.0));
            for (double s = clear; s + 1.0 < length - clear; s += 20.0)
                AddWall(PolylinePoint(rail, s), PolylinePoint(rail, std::min(s + 20.0, length - clear)), 0.3, 0.35, 0.8,
                        Material::kMetal, world);
            const auto verge = OffsetPolyline(edge.polyline, side * (config.road_half_width + 2.5));
            Eigen::Vector2d tangent;
            if (side > 0)
                for (double s = clear; s < length - clear; s += config.lamp_spacing) {
                    const Eigen::Vector2d base = PolylinePoint(verge, s, &tangent);
                    AddLamp(base, -Eigen::Vector2d(tangent.y(), -tangent.x()), rng, world);
                }
            for (double s = clear + Uniform(rng, 0, config.sign_spacing); s < length - clear;
                 s += config.sign_spacing * Uniform(rng, 0.7, 1.3)) {
                const Eigen::Vector2d base = PolylinePoint(verge, s, &tangent);
                const Eigen::Vector2d normal(-tangent.y(), tangent.x());
                const double g = world.ground.Height(base.x(), base.y());
                world.cylinders.push_back({base - 1.5 * tangent, 0.08, g - 0.5, g + 5.5, Material::kMetal});
                world.cylinders.push_back({base + 1.5 * tangent, 0.08, g - 0.5, g + 5.5, Material::kMetal});
                AddStandingBox(base, std::atan2(normal.y(), normal.x()) + kPi / 2, Eigen::Vector2d(2.0, 0.05), 3.5, 5.5,
                               Material::kMetal, world);
            }
            for (double s = clear; s < length - clear; s += 25.0)
                if (Uniform(rng, 0, 1) < config.tree_probability)
                    AddTree(PolylinePoint(OffsetPolyline(edge.polyline, side * (config.road_half_width + Uniform(rng, 6, 20))), s),
                            rng, world);
            // Own draws (the layout above stays): the guard rail's posts, and bushes, hedges and posts on
            // the verge; a rail alone is the same all along the road, which leaves the motion along it free.
            for (double s = clear; s + 1.0 < length - clear && config.rail_post_spacing > 0.0; s += config.rail_post_spacing) {
                const Eigen::Vector2d post = PolylinePoint(rail, s);
                const double g = world.ground.Height(post.x(), post.y());
                world.cylinders.push_back({post, 0.06, g - 0.3, g + 0.7, Material::kMetal});
            }
            AddRoadsideClutter(edge.polyline, clear, length - clear, side * (config.road_half_width + 2.0),
                               side * (config.road_half_width + 14.0), config.bush_spacing, clutter_rng, world);
            AddVerge(edge.polyline, clear, length - clear, side, config, verge_rng, world);
        }
        // Bridges over the road: a deck on two piers beyond the rails.
        for (double s = clear + Uniform(verge_rng, 0, config.overpass_spacing);
             config.overpass_spacing > 0.0 && s < length - clear; s += config.overpass_spacing * Uniform(verge_rng, 0.6, 1.4)) {
            Eigen::Vector2d tangent;
            const Eigen::Vector2d centre = PolylinePoint(edge.polyline, s, &tangent);
            const Eigen::Vector2d normal(-tangent.y(), tangent.x());
            const double span = config.road_half_width + Uniform(verge_rng, 5.0, 12.0);
            const double deck = Uniform(verge_rng, 5.2, 6.5);
            AddWall(centre - span * normal, centre + span * normal, Uniform(verge_rng, 8.0, 14.0), deck, deck + 1.2,
                    Material::kWall, world);
            for (int pier = -1; pier <= 1; pier += 2)
                AddStandingBox(centre + pier * (config.road_half_width + 3.0) * normal, std::atan2(normal.y(), normal.x()),
                               Eigen::Vector2d(0.6, 3.0), -0.5, deck, Material::kWall, world);
        }
        for (std::size_t i = 1; i < edge.polyline.size(); ++i)
            world.roads.push_back({edge.polyline[i - 1], edge.polyline[i], config.road_half_width});
    }
    AddMovingCars(config.moving_cars, 18.0, 30.0, rng, world);
    return world;
}

}  // namespace revisit
