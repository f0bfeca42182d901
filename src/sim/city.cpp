#include <algorithm>
#include <cmath>
#include <queue>
#include <random>
#include <unordered_map>

#include "sim/generators.hpp"
#include "sim/objects.hpp"

namespace revisit {
namespace {

constexpr double kPi = 3.14159265358979323846;

double Uniform(std::mt19937& rng, double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng); }
bool Chance(std::mt19937& rng, double p) { return Uniform(rng, 0.0, 1.0) < p; }

bool Connected(const StreetGraph& graph, const std::vector<bool>& removed) {
    std::vector<std::vector<int>> neighbours(graph.nodes.size());
    for (std::size_t e = 0; e < graph.edges.size(); ++e) {
        if (removed[e]) continue;
        neighbours[graph.edges[e].a].push_back(graph.edges[e].b);
        neighbours[graph.edges[e].b].push_back(graph.edges[e].a);
    }
    std::vector<bool> seen(graph.nodes.size(), false);
    std::queue<int> open;
    open.push(0);
    seen[0] = true;
    std::size_t count = 1;
    while (!open.empty()) {
        const int n = open.front();
        open.pop();
        for (int m : neighbours[n])
            if (!seen[m]) seen[m] = true, ++count, open.push(m);
    }
    return count == graph.nodes.size();
}

/// Lamps, trees, parked cars, kerbs and moving cars along one street (METHOD-independent scenery).
void FurnishStreet(const StreetGraph::Edge& edge, const CityConfig& config, const std::vector<double>& ring,
                   std::mt19937& rng, std::mt19937& clutter_rng, World& world) {
    const double length = edge.length;
    // Keep junctions (and roundabout rings) free: furniture starts `clear_a` from node a, ends `clear_b` before b.
    const double clear = config.road_half_width + config.sidewalk;
    const double clear_a = std::max(clear, ring[edge.a] + config.road_half_width + 1.5);
    const double clear_b = std::max(clear, ring[edge.b] + config.road_half_width + 1.5);
    if (length < clear_a + clear_b + 5.0) return;
    const bool trees = Chance(rng, config.tree_street_fraction);
    for (int side = -1; side <= 1; side += 2) {
        const auto kerb_line = OffsetPolyline(edge.polyline, side * config.road_half_width);
        // Kerb stones in short pieces so they follow the ground.
        for (double s = clear_a; s + 1.0 < length - clear_b; s += 8.0) {
            const Eigen::Vector2d a = PolylinePoint(kerb_line, s);
            const Eigen::Vector2d b = PolylinePoint(kerb_line, std::min(s + 8.0, length - clear_b));
            AddWall(a, b, 0.25, -0.3, 0.15, Material::kWall, world);
        }
        Eigen::Vector2d tangent;
        for (double s = clear_a + Uniform(rng, 0.0, 10.0); s < length - clear_b;
             s += Uniform(rng, config.lamp_spacing_min, config.lamp_spacing_max)) {
            const Eigen::Vector2d base = PolylinePoint(OffsetPolyline(edge.polyline, side * (config.road_half_width + 0.8)), s, &tangent);
            const Eigen::Vector2d towards_road = side * Eigen::Vector2d(-tangent.y(), tangent.x());
            AddLamp(base, towards_road, rng, world);
        }
        if (trees) {
            const auto tree_line = OffsetPolyline(edge.polyline, side * (config.road_half_width + 2.2));
            for (double s = clear_a + Uniform(rng, 3.0, 8.0); s < length - clear_b; s += Uniform(rng, 8.0, 14.0))
                AddTree(PolylinePoint(tree_line, s), rng, world);
        }
        const auto parking_line = OffsetPolyline(edge.polyline, side * (config.road_half_width - 1.1));
        for (double s = clear_a + 3.0; s + 3.0 < length - clear_b; s += 6.0) {
            if (!Chance(rng, config.parked_car_density)) continue;
            const Eigen::Vector2d center = PolylinePoint(parking_line, s, &tangent);
            float from = -1e9f, until = 1e9f;
            if (Chance(rng, config.transient_car_fraction)) {
                from = static_cast<float>(Uniform(rng, -60.0, config.transient_horizon));
                until = from + static_cast<float>(Uniform(rng, 60.0, 300.0));
            }
            AddParkedCar(center, std::atan2(tangent.y(), tangent.x()), from, until, world);
        }
        // Own draws: the clutter does not move anything placed above.
        AddRoadsideClutter(edge.polyline, clear_a, length - clear_b, side * (config.road_half_width + 0.7),
                           side * (config.road_half_width + config.sidewalk + 1.5), config.bush_spacing, clutter_rng, world);
    }
    for (std::size_t i = 1; i < edge.polyline.size(); ++i)
        world.roads.push_back({edge.polyline[i - 1], edge.polyline[i], config.road_half_width});
}

/// Buildings (and fences in the gaps) along one side of a block, from corner p to corner q
/// (counter-clockwise, so the block interior is on the left).
void BuildBlockSide(const Eigen::Vector2d& p, const Eigen::Vector2d& q, double ring_p, double ring_q, bool curved,
                    const CityConfig& config, std::mt19937& rng, World& world) {
    const double side_length = (q - p).norm();
    const Eigen::Vector2d along = (q - p) / side_length;
    const Eigen::Vector2d inward(-along.y(), along.x());
    const double corner = config.road_half_width + config.sidewalk + 2.0;
    const double clear_p = std::max(corner, ring_p + config.road_half_width + config.sidewalk + 1.0);
    const double clear_q = std::max(corner, ring_q + config.road_half_width + config.sidewalk + 1.0);
    const double setback_base = config.road_half_width + config.sidewalk + (curved ? config.curve_amplitude : 0.0);
    const double max_depth = std::max(8.0, (0.5 * config.block_size - setback_base) / 1.6);
    double u = clear_p + Uniform(rng, 0.0, 4.0);
    while (u < side_length - clear_q - 8.0) {
        const double width = std::min(Uniform(rng, 10.0, 30.0), side_length - clear_q - u);
        const double setback = setback_base + Uniform(rng, 0.3, 3.0);
        BuildingSpec spec;
        spec.along = along;
        spec.away = inward;
        spec.front_center = p + along * (u + 0.5 * width) + inward * setback;
        spec.width = width;
        spec.depth = Uniform(rng, 8.0, std::max(9.0, max_depth));
        spec.height = Uniform(rng, config.min_building_height, config.max_building_height);
        AddBuilding(spec, rng, world);
        u += width;
        const double gap = Chance(rng, 0.4) ? 0.0 : Uniform(rng, 2.0, 10.0);
        if (gap > 0.0 && Chance(rng, config.fence_probability)) {
            const Eigen::Vector2d a = p + along * u + inward * (setback_base + 0.5);
            AddWall(a, a + along * std::min(gap, side_length - clear_q - u), 0.2, -0.5, Uniform(rng, 1.0, 2.5),
                    Material::kWall, world);
        }
        u += gap;
    }
}

/// Drops the boxes (from index `first` on) that reach within `clearance` of a street centre line or a
/// roundabout ring: deep buildings at skewed block corners can otherwise reach the cross street.
void ClearStreets(const StreetGraph& streets, std::size_t first, double clearance, World& world) {
    const double cell = clearance;
    std::unordered_map<long long, std::vector<Eigen::Vector2d>> grid;
    auto key = [&](const Eigen::Vector2d& p, int dx, int dy) {
        return (static_cast<long long>(std::floor(p.x() / cell)) + dx) * 1000003LL + static_cast<long long>(std::floor(p.y() / cell)) + dy;
    };
    auto add = [&](const Eigen::Vector2d& p) { grid[key(p, 0, 0)].push_back(p); };
    for (const auto& edge : streets.edges)
        for (double s = 0.0; s <= edge.length; s += 1.0) add(PolylinePoint(edge.polyline, s));
    for (std::size_t n = 0; n < streets.nodes.size(); ++n)
        for (int k = 0; k < 64 && streets.RoundaboutRadius(static_cast<int>(n)) > 0.0; ++k)
            add(streets.nodes[n] + streets.RoundaboutRadius(static_cast<int>(n)) *
                                       Eigen::Vector2d(std::cos(k * kPi / 32), std::sin(k * kPi / 32)));
    auto near = [&](const Eigen::Vector2d& p) {
        for (int dx = -1; dx <= 1; ++dx)
            for (int dy = -1; dy <= 1; ++dy) {
                const auto it = grid.find(key(p, dx, dy));
                if (it == grid.end()) continue;
                for (const auto& q : it->second)
                    if ((q - p).norm() < clearance) return true;
            }
        return false;
    };
    std::vector<OrientedBox> kept(world.boxes.begin(), world.boxes.begin() + static_cast<long>(first));
    for (std::size_t i = first; i < world.boxes.size(); ++i) {
        const OrientedBox& b = world.boxes[i];
        const Eigen::Vector2d ax(std::cos(b.yaw), std::sin(b.yaw)), ay(-ax.y(), ax.x());
        bool blocked = false;
        for (int side = 0; side < 4 && !blocked; ++side) {  // the perimeter, every metre
            const double hx = b.half_size.x(), hy = b.half_size.y();
            const bool along_x = side < 2;
            const double fixed = (side % 2 == 0 ? -1.0 : 1.0) * (along_x ? hy : hx);
            const double half = along_x ? hx : hy;
            for (double t = -half; t <= half + 1e-9 && !blocked; t += std::max(0.05, std::min(1.0, half)))
                blocked = near(b.center + (along_x ? t * ax + fixed * ay : fixed * ax + t * ay));
        }
        if (!blocked) kept.push_back(b);
    }
    world.boxes = std::move(kept);
}

}  // namespace

World GenerateCity(const CityConfig& config, std::uint64_t seed) {
    std::mt19937 rng(static_cast<std::uint32_t>(seed * 2654435761u + 17u));
    World world;
    world.kind = "city";
    world.ground.slope_x = config.ground_slope * std::cos(Uniform(rng, 0.0, 2.0 * kPi));
    world.ground.slope_y = config.ground_slope * std::sin(Uniform(rng, 0.0, 2.0 * kPi));
    world.ground.amplitude = config.ground_amplitude;
    world.ground.wavelength = Uniform(rng, 250.0, 450.0);
    world.lane_offset = 0.5 * config.road_half_width - 0.5;
    world.ground.relief = config.ground_relief;
    world.ground.roughness = config.ground_roughness;
    world.ground.seed = seed * 0x9E3779B97F4A7C15ULL + 0x6A09E667ULL;  // not from rng: the layout stays as it was
    world.foliage_free_path = config.foliage_free_path;

    const int nx = config.blocks_x + 1;
    const int ny = config.blocks_y + 1;
    auto node = [&](int i, int j) { return j * nx + i; };
    StreetGraph& graph = world.streets;
    for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i)
            graph.nodes.emplace_back(i * config.block_size + Uniform(rng, -config.node_jitter, config.node_jitter),
                                     j * config.block_size + Uniform(rng, -config.node_jitter, config.node_jitter));
    // Candidate streets; horizontal first, then vertical. edge_of[k] maps (i, j, direction) to an edge.
    std::vector<int> h_edge(nx * ny, -1), v_edge(nx * ny, -1);
    std::vector<bool> curved;
    auto add = [&](int a, int b) {
        const bool bend = Chance(rng, config.curved_fraction);
        std::vector<Eigen::Vector2d> polyline;
        const Eigen::Vector2d pa = graph.nodes[a], pb = graph.nodes[b];
        const Eigen::Vector2d dir = (pb - pa).normalized();
        const Eigen::Vector2d normal(-dir.y(), dir.x());
        const double sign = Chance(rng, 0.5) ? 1.0 : -1.0;
        const int pieces = bend ? 12 : 1;
        for (int k = 0; k <= pieces; ++k) {
            const double f = static_cast<double>(k) / pieces;
            polyline.push_back(pa + f * (pb - pa) + normal * (bend ? sign * config.curve_amplitude * std::sin(kPi * f) : 0.0));
        }
        curved.push_back(bend);
        return graph.AddEdge(a, b, polyline);
    };
    for (int j = 0; j < ny; ++j)
        for (int i = 0; i + 1 < nx; ++i) h_edge[node(i, j)] = add(node(i, j), node(i + 1, j));
    for (int j = 0; j + 1 < ny; ++j)
        for (int i = 0; i < nx; ++i) v_edge[node(i, j)] = add(node(i, j), node(i, j + 1));

    // Remove some interior streets, keeping every intersection at degree >= 3 and the graph connected.
    std::vector<bool> removed(graph.edges.size(), false);
    std::vector<int> degree(graph.nodes.size(), 0);
    for (const auto& e : graph.edges) ++degree[e.a], ++degree[e.b];
    for (std::size_t e = 0; e < graph.edges.size(); ++e) {
        if (!Chance(rng, config.removed_fraction)) continue;
        const auto& edge = graph.edges[e];
        if (degree[edge.a] <= 3 || degree[edge.b] <= 3) continue;
        removed[e] = true;
        if (!Connected(graph, removed)) {
            removed[e] = false;
            continue;
        }
        --degree[edge.a], --degree[edge.b];
    }

    // Roundabouts at some four-way junctions: a raised island with a tree, driven around.
    std::vector<double> ring(graph.nodes.size(), 0.0);
    for (std::size_t n = 0; n < graph.nodes.size(); ++n) {
        if (degree[n] != 4 || !Chance(rng, config.roundabout_fraction)) continue;
        ring[n] = config.roundabout_radius;
        const Eigen::Vector2d c = graph.nodes[n];
        const double g = world.ground.Height(c.x(), c.y());
        world.cylinders.push_back({c, 0.5 * config.roundabout_radius, g - 0.5, g + 0.3, Material::kWall});
        AddTree(c, rng, world);
    }

    // Buildings along the four sides of every block.
    const std::size_t buildings_first = world.boxes.size();
    for (int j = 0; j + 1 < ny; ++j)
        for (int i = 0; i + 1 < nx; ++i) {
            const int corners[4] = {node(i, j), node(i + 1, j), node(i + 1, j + 1), node(i, j + 1)};
            const int sides[4] = {h_edge[node(i, j)], v_edge[node(i + 1, j)], h_edge[node(i, j + 1)], v_edge[node(i, j)]};
            for (int k = 0; k < 4; ++k)
                BuildBlockSide(graph.nodes[corners[k]], graph.nodes[corners[(k + 1) % 4]], ring[corners[k]],
                               ring[corners[(k + 1) % 4]], curved[sides[k]], config, rng, world);
        }

    if (config.outer_frontage) {
        std::mt19937 outer_rng(static_cast<std::uint32_t>(seed * 69069u + 7u));  // own stream: the layout above stays
        const auto outer = [&](int a, int b, int edge) {  // buildings on the left of a -> b, i.e. outside
            BuildBlockSide(graph.nodes[a], graph.nodes[b], ring[a], ring[b], curved[edge], config, outer_rng, world);
        };
        for (int i = 0; i + 1 < nx; ++i) {
            outer(node(i + 1, 0), node(i, 0), h_edge[node(i, 0)]);                   // south side
            outer(node(i, ny - 1), node(i + 1, ny - 1), h_edge[node(i, ny - 1)]);   // north side
        }
        for (int j = 0; j + 1 < ny; ++j) {
            outer(node(0, j), node(0, j + 1), v_edge[node(0, j)]);                   // west side
            outer(node(nx - 1, j + 1), node(nx - 1, j), v_edge[node(nx - 1, j)]);   // east side
        }
    }

    // Keep the remaining streets; clear them of buildings; furnish them.
    StreetGraph kept;
    kept.nodes = graph.nodes;
    for (std::size_t e = 0; e < graph.edges.size(); ++e)
        if (!removed[e]) kept.AddEdge(graph.edges[e].a, graph.edges[e].b, graph.edges[e].polyline);
    kept.roundabout_radius = ring;
    world.streets = std::move(kept);
    ClearStreets(world.streets, buildings_first, config.road_half_width + 1.0, world);
    for (const auto& n : world.streets.nodes) world.roads.push_back({n, n, config.road_half_width * 1.3});

    std::mt19937 clutter_rng(static_cast<std::uint32_t>(seed * 40503u + 101u));
    for (const auto& edge : world.streets.edges) FurnishStreet(edge, config, ring, rng, clutter_rng, world);

    AddMovingCars(config.moving_cars, 5.0, 12.0, rng, world);
    return world;
}

}  // namespace revisit
