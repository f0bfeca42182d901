#include <Eigen/Eigenvalues>
#include <cmath>
#include <random>
#include <unordered_map>

#include "sim/generators.hpp"
#include "sim/objects.hpp"

namespace revisit {
namespace {

double Uniform(std::mt19937& rng, double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng); }

/// Distance queries against the route's samples (hash grid with cells of the clearance).
class RouteDistance {
  public:
    RouteDistance(const std::vector<Eigen::Vector2d>& samples, double cell) : samples_(samples), cell_(cell) {
        for (std::size_t i = 0; i < samples.size(); ++i) grid_.emplace(Key(samples[i], 0, 0), i);
    }
    /// True when some route sample is closer than `radius` (<= cell) to p.
    bool Near(const Eigen::Vector2d& p, double radius) const {
        for (int dx = -1; dx <= 1; ++dx)
            for (int dy = -1; dy <= 1; ++dy) {
                const auto range = grid_.equal_range(Key(p, dx, dy));
                for (auto it = range.first; it != range.second; ++it)
                    if ((samples_[it->second] - p).norm() < radius) return true;
            }
        return false;
    }

  private:
    long long Key(const Eigen::Vector2d& p, int dx, int dy) const {
        const long long x = static_cast<long long>(std::floor(p.x() / cell_)) + dx;
        const long long y = static_cast<long long>(std::floor(p.y() / cell_)) + dy;
        return x * 1000003LL + y;
    }
    const std::vector<Eigen::Vector2d>& samples_;
    double cell_;
    std::unordered_multimap<long long, std::size_t> grid_;
};

/// Every corner of every box and every pole/crown added since the given sizes stays clear of the route.
bool Clear(const World& world, std::size_t boxes, std::size_t cylinders, std::size_t spheres, const RouteDistance& route,
           double clearance) {
    for (std::size_t i = boxes; i < world.boxes.size(); ++i) {
        const auto& b = world.boxes[i];
        const Eigen::Vector2d ax(std::cos(b.yaw), std::sin(b.yaw)), ay(-ax.y(), ax.x());
        for (double u : {-1.0, -0.5, 0.0, 0.5, 1.0})
            for (double v : {-1.0, 0.0, 1.0})
                if (route.Near(b.center + u * b.half_size.x() * ax + v * b.half_size.y() * ay, clearance)) return false;
    }
    for (std::size_t i = cylinders; i < world.cylinders.size(); ++i)
        if (route.Near(world.cylinders[i].center, clearance)) return false;
    for (std::size_t i = spheres; i < world.spheres.size(); ++i)
        if (route.Near(world.spheres[i].center.head<2>(), clearance)) return false;
    return true;
}

}  // namespace

World GenerateAroundTrajectory(const Poses& poses, const AroundTrajectoryConfig& config, std::uint64_t seed) {
    std::mt19937 rng(static_cast<std::uint32_t>(seed * 668265263u + 13u));
    World world;
    world.kind = "around_trajectory";
    world.lane_offset = 0.0;
    world.ground.relief = config.city.ground_relief;
    world.ground.roughness = config.city.ground_roughness;
    world.ground.seed = seed * 0x9E3779B97F4A7C15ULL + 0x3C6EF372ULL;
    world.foliage_free_path = config.city.foliage_free_path;
    if (poses.size() < 2) return world;
    // The ground plane holds the two directions of largest spread; the third is "up".
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    for (const auto& T : poses) mean += T.translation();
    mean /= static_cast<double>(poses.size());
    Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
    for (const auto& T : poses) covariance += (T.translation() - mean) * (T.translation() - mean).transpose();
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(covariance);
    const Eigen::Vector3d e1 = solver.eigenvectors().col(2), e2 = solver.eigenvectors().col(1);
    std::vector<Eigen::Vector2d> route;
    for (const auto& T : poses) {
        const Eigen::Vector3d d = T.translation() - mean;
        const Eigen::Vector2d p(d.dot(e1), d.dot(e2));
        if (route.empty() || (p - route.back()).norm() >= config.sample_spacing) route.push_back(p);
    }
    world.streets.nodes = {route.front(), route.back()};
    world.streets.AddEdge(0, 1, route);
    const RouteDistance near_route(route, config.clearance + 2.0);
    const CityConfig& city = config.city;
    for (std::size_t i = 1; i < route.size(); ++i)
        world.roads.push_back({route[i - 1], route[i], std::min(city.road_half_width, config.clearance)});

    // Walk along the route and try to place objects on both sides; anything too close is taken back.
    const double length = PolylineLength(route);
    auto place = [&](auto&& add, double clearance) {
        const std::size_t b = world.boxes.size(), c = world.cylinders.size(), s = world.spheres.size();
        add();
        if (!Clear(world, b, c, s, near_route, clearance)) {
            world.boxes.resize(b);
            world.cylinders.resize(c);
            world.spheres.resize(s);
        }
    };
    Eigen::Vector2d tangent;
    for (int side = -1; side <= 1; side += 2) {
        for (double s = 0.0; s < length;) {
            const double width = Uniform(rng, 10.0, 28.0);
            const Eigen::Vector2d p = PolylinePoint(route, s + 0.5 * width, &tangent);
            const Eigen::Vector2d away = side * Eigen::Vector2d(-tangent.y(), tangent.x());
            BuildingSpec spec;
            spec.along = side > 0 ? tangent : Eigen::Vector2d(-tangent);
            spec.away = away;
            spec.front_center = p + away * (config.clearance + city.sidewalk + Uniform(rng, 0.5, 4.0));
            spec.width = width;
            spec.depth = Uniform(rng, 8.0, 20.0);
            spec.height = Uniform(rng, city.min_building_height, city.max_building_height);
            place([&] { AddBuilding(spec, rng, world); }, config.clearance);
            s += width + (Uniform(rng, 0, 1) < 0.4 ? 0.0 : Uniform(rng, 2.0, 12.0));
        }
        for (double s = Uniform(rng, 0, 10); s < length; s += Uniform(rng, city.lamp_spacing_min, city.lamp_spacing_max)) {
            const Eigen::Vector2d p = PolylinePoint(route, s, &tangent);
            const Eigen::Vector2d away = side * Eigen::Vector2d(-tangent.y(), tangent.x());
            place([&] { AddLamp(p + away * (config.clearance + 0.5), -away, rng, world); }, config.clearance);
        }
        for (double s = Uniform(rng, 0, 10); s < length; s += Uniform(rng, 8.0, 20.0)) {
            const Eigen::Vector2d p = PolylinePoint(route, s, &tangent);
            const Eigen::Vector2d away = side * Eigen::Vector2d(-tangent.y(), tangent.x());
            if (Uniform(rng, 0, 1) < city.tree_street_fraction)
                place([&] { AddTree(p + away * (config.clearance + 3.5), rng, world); }, config.clearance);
            else if (Uniform(rng, 0, 1) < city.parked_car_density)
                place([&] {
                    AddParkedCar(p + away * config.parking_offset, std::atan2(tangent.y(), tangent.x()), -1e9f, 1e9f, world);
                }, config.near_clearance);
        }
    }
    // Roadside clutter between the parked cars and the buildings, with its own draws (the layout above
    // stays as it was): real streets are lined with bushes, hedges and posts (src/sim/README.md).
    std::mt19937 clutter_rng(static_cast<std::uint32_t>(seed * 40503u + 101u));
    auto accept = [&](std::size_t b, std::size_t c, std::size_t s) {
        return Clear(world, b, c, s, near_route, config.near_clearance + 1.0);
    };
    for (int side = -1; side <= 1; side += 2) {
        AddRoadsideClutter(route, 0.0, length, -side * (config.parking_offset + 1.5),
                           -side * (config.clearance + city.sidewalk), city.bush_spacing, clutter_rng, world, accept);
        // Kerbs at the road edge and, along the property line, garden walls, fences and hedges in pieces.
        const auto kerb_line = OffsetPolyline(route, -side * (config.parking_offset + 1.2));
        const auto property_line = OffsetPolyline(route, -side * (config.clearance + city.sidewalk));
        for (double s = 0.0; s < length; s += 8.0) {
            const std::size_t b = world.boxes.size(), c = world.cylinders.size(), e = world.spheres.size();
            AddWall(PolylinePoint(kerb_line, s), PolylinePoint(kerb_line, std::min(s + 8.0, length)), 0.25, -0.3, 0.15,
                    Material::kWall, world);
            if (!accept(b, c, e)) world.boxes.resize(b);
        }
        for (double s = 0.0; s < length;) {
            const double piece = Uniform(clutter_rng, 6.0, 24.0);
            const double kind = Uniform(clutter_rng, 0.0, 1.0);
            const double height = Uniform(clutter_rng, 0.8, 1.8);
            for (double u = s; u < std::min(s + piece, length) && kind < city.fence_probability; u += 4.0) {
                const std::size_t b = world.boxes.size(), c = world.cylinders.size(), e = world.spheres.size();
                const Eigen::Vector2d a = PolylinePoint(property_line, u);
                const Eigen::Vector2d z = PolylinePoint(property_line, std::min({u + 4.0, s + piece, length}));
                if (kind < 0.5 * city.fence_probability)
                    AddWall(a, z, 0.15, -0.3, height, Material::kWall, world);
                else
                    AddHedge(a, z, clutter_rng, world);
                if (!accept(b, c, e)) world.boxes.resize(b), world.spheres.resize(e);
            }
            s += piece;
        }
    }
    return world;
}

}  // namespace revisit
