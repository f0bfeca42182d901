#include "sim/objects.hpp"

#include <algorithm>
#include <cmath>

namespace revisit {
namespace {

double Uniform(std::mt19937& rng, double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng); }

double Yaw(const Eigen::Vector2d& direction) { return std::atan2(direction.y(), direction.x()); }

/// Box given in the building frame (u along the street, v away from it) relative to the facade centre.
void AddPart(const BuildingSpec& spec, double u0, double u1, double v0, double v1, double z0, double z1,
             Material material, World& world) {
    const double ground = world.ground.Height(spec.front_center.x(), spec.front_center.y());
    OrientedBox box;
    box.center = spec.front_center + spec.along * (0.5 * (u0 + u1)) + spec.away * (0.5 * (v0 + v1));
    box.half_size = Eigen::Vector2d(0.5 * std::abs(u1 - u0), 0.5 * std::abs(v1 - v0));
    box.yaw = Yaw(spec.along);
    box.z_min = ground - 1.0;  // sunk so that sloped ground never shows a gap
    box.z_max = ground + z1;
    if (z0 > 0.0) box.z_min = ground + z0;
    box.material = material;
    world.boxes.push_back(box);
}

}  // namespace

void AddBuilding(const BuildingSpec& spec, std::mt19937& rng, World& world) {
    const double w = spec.width;
    const double d = spec.depth;
    const double h = spec.height;
    const int shape = std::uniform_int_distribution<int>(0, 3)(rng);
    switch (shape) {
        case 0:  // rectangle
            AddPart(spec, -w / 2, w / 2, 0.0, d, 0.0, h, Material::kBuilding, world);
            break;
        case 1: {  // L: front slab plus a deep wing at one end
            const double wing = Uniform(rng, 0.3, 0.5) * w;
            const double side = (rng() & 1u) ? 1.0 : -1.0;
            AddPart(spec, -w / 2, w / 2, 0.0, 0.5 * d, 0.0, h, Material::kBuilding, world);
            AddPart(spec, side * w / 2 - side * wing, side * w / 2, 0.5 * d, 1.6 * d, 0.0, h * Uniform(rng, 0.6, 1.0),
                    Material::kBuilding, world);
            break;
        }
        case 2: {  // U: two wings towards the back, a courtyard between them
            const double wing = Uniform(rng, 0.2, 0.3) * w;
            AddPart(spec, -w / 2, w / 2, 0.0, 0.4 * d, 0.0, h, Material::kBuilding, world);
            AddPart(spec, -w / 2, -w / 2 + wing, 0.4 * d, 1.4 * d, 0.0, h, Material::kBuilding, world);
            AddPart(spec, w / 2 - wing, w / 2, 0.4 * d, 1.4 * d, 0.0, h * Uniform(rng, 0.5, 1.0), Material::kBuilding,
                    world);
            break;
        }
        default: {  // stepped: two blocks with different set-backs and heights (a recess in the facade)
            const double split = Uniform(rng, -0.2, 0.2) * w;
            const double recess = Uniform(rng, 1.5, 4.0);
            AddPart(spec, -w / 2, split, 0.0, d, 0.0, h, Material::kBuilding, world);
            AddPart(spec, split, w / 2, recess, d, 0.0, h * Uniform(rng, 0.5, 1.2), Material::kBuilding, world);
            break;
        }
    }
    // Facade protrusions (bays, porches, shop fronts) on the street side.
    const int protrusions = std::uniform_int_distribution<int>(0, 3)(rng);
    for (int i = 0; i < protrusions; ++i) {
        const double pw = Uniform(rng, 2.0, 5.0);
        const double u = Uniform(rng, -w / 2 + pw / 2, w / 2 - pw / 2);
        const double depth = Uniform(rng, 0.8, 2.0);
        const bool ground_floor = (rng() & 1u) != 0;
        const double z0 = ground_floor ? 0.0 : Uniform(rng, 2.5, 4.0);
        const double z1 = ground_floor ? Uniform(rng, 2.5, 4.0) : std::max(z0 + 2.0, h * Uniform(rng, 0.5, 0.9));
        AddPart(spec, u - pw / 2, u + pw / 2, -depth, 0.0, z0, std::min(z1, h), ground_floor ? Material::kGlass
                                                                                             : Material::kBuilding,
                world);
    }
}

void AddLamp(const Eigen::Vector2d& base, const Eigen::Vector2d& towards_road, std::mt19937& rng, World& world) {
    const double ground = world.ground.Height(base.x(), base.y());
    const double height = Uniform(rng, 6.0, 9.0);
    world.cylinders.push_back({base, 0.09, ground - 0.5, ground + height, Material::kMetal});
    const Eigen::Vector2d dir = towards_road.normalized();
    const double arm = Uniform(rng, 1.0, 2.0);
    OrientedBox arm_box;
    arm_box.center = base + dir * (arm / 2);
    arm_box.half_size = Eigen::Vector2d(arm / 2, 0.06);
    arm_box.yaw = Yaw(dir);
    arm_box.z_min = ground + height - 0.15;
    arm_box.z_max = ground + height;
    arm_box.material = Material::kMetal;
    world.boxes.push_back(arm_box);
    world.spheres.push_back({Eigen::Vector3d(base.x() + dir.x() * arm, base.y() + dir.y() * arm, ground + height - 0.2),
                             0.3, Material::kMetal});
}

void AddTree(const Eigen::Vector2d& base, std::mt19937& rng, World& world) {
    const double ground = world.ground.Height(base.x(), base.y());
    const double trunk = Uniform(rng, 2.0, 3.5);
    const double crown = Uniform(rng, 1.5, 3.0);
    world.cylinders.push_back({base, Uniform(rng, 0.12, 0.3), ground - 0.5, ground + trunk + crown, Material::kVegetation});
    world.spheres.push_back({Eigen::Vector3d(base.x(), base.y(), ground + trunk + crown), crown, Material::kVegetation});
    if (rng() & 1u)
        world.spheres.push_back({Eigen::Vector3d(base.x() + Uniform(rng, -0.8, 0.8), base.y() + Uniform(rng, -0.8, 0.8),
                                                 ground + trunk + 1.6 * crown),
                                 0.7 * crown, Material::kVegetation});
}

void AddBush(const Eigen::Vector2d& base, std::mt19937& rng, World& world) {
    const double ground = world.ground.Height(base.x(), base.y());
    const int parts = std::uniform_int_distribution<int>(2, 3)(rng);
    for (int i = 0; i < parts; ++i) {
        const double r = Uniform(rng, 0.4, 1.0);
        world.spheres.push_back({Eigen::Vector3d(base.x() + Uniform(rng, -0.6, 0.6), base.y() + Uniform(rng, -0.6, 0.6),
                                                 ground + Uniform(rng, 0.1, 0.7) * r + 0.2),
                                 r, Material::kVegetation});
    }
}

void AddHedge(const Eigen::Vector2d& a, const Eigen::Vector2d& b, std::mt19937& rng, World& world) {
    const double length = (b - a).norm();
    const double height = Uniform(rng, 1.0, 2.2);
    for (double s = 0.0; s <= length; s += Uniform(rng, 0.6, 1.0)) {
        const Eigen::Vector2d p = a + (b - a) * (s / std::max(length, 1e-9));
        const double ground = world.ground.Height(p.x(), p.y());
        const double r = 0.5 * height * Uniform(rng, 0.8, 1.1);
        world.spheres.push_back({Eigen::Vector3d(p.x(), p.y(), ground + height - r), r, Material::kVegetation});
    }
}

void AddSmallFurniture(const Eigen::Vector2d& base, const Eigen::Vector2d& along, std::mt19937& rng, World& world) {
    const double ground = world.ground.Height(base.x(), base.y());
    const double kind = Uniform(rng, 0.0, 1.0);
    if (kind < 0.5) {  // sign post with a panel facing the road
        const double height = Uniform(rng, 2.0, 3.2);
        world.cylinders.push_back({base, 0.04, ground - 0.3, ground + height, Material::kMetal});
        AddStandingBox(base, Yaw(along), Eigen::Vector2d(Uniform(rng, 0.25, 0.6), 0.03), height - 0.7, height,
                       Material::kMetal, world);
    } else if (kind < 0.8) {  // bollard
        world.cylinders.push_back({base, Uniform(rng, 0.08, 0.15), ground - 0.3, ground + Uniform(rng, 0.6, 1.1),
                                   Material::kMetal});
    } else {  // bin, electrical box
        AddStandingBox(base, Yaw(along), Eigen::Vector2d(Uniform(rng, 0.3, 0.6), Uniform(rng, 0.3, 0.5)), -0.2,
                       Uniform(rng, 0.9, 1.5), Material::kFurniture, world);
    }
}

void AddRoadsideClutter(const std::vector<Eigen::Vector2d>& line, double s0, double s1, double near, double far,
                        double spacing, std::mt19937& rng, World& world,
                        const std::function<bool(std::size_t, std::size_t, std::size_t)>& accept) {
    if (spacing <= 0.0) return;
    Eigen::Vector2d tangent;
    for (double s = s0 + Uniform(rng, 0.0, spacing); s < s1; s += Uniform(rng, 0.3, 1.7) * spacing) {
        const Eigen::Vector2d p = PolylinePoint(line, s, &tangent);
        const Eigen::Vector2d right(tangent.y(), -tangent.x());
        const double offset = Uniform(rng, std::min(near, far), std::max(near, far));
        const Eigen::Vector2d base = p + right * offset;
        const std::size_t b = world.boxes.size(), c = world.cylinders.size(), e = world.spheres.size();
        const double kind = Uniform(rng, 0.0, 1.0);
        if (kind < 0.45) {
            AddBush(base, rng, world);
        } else if (kind < 0.65) {
            const double length = std::min(Uniform(rng, 4.0, 12.0), s1 - s);
            const Eigen::Vector2d end = PolylinePoint(line, s + length, &tangent);
            AddHedge(base, end + Eigen::Vector2d(tangent.y(), -tangent.x()) * offset, rng, world);
            s += length;
        } else {
            AddSmallFurniture(base, tangent, rng, world);
        }
        if (accept && !accept(b, c, e)) {
            world.boxes.resize(b);
            world.cylinders.resize(c);
            world.spheres.resize(e);
        }
    }
}

void AddParkedCar(const Eigen::Vector2d& center, double yaw, float from, float until, World& world) {
    const double ground = world.ground.Height(center.x(), center.y());
    OrientedBox body;
    body.center = center;
    body.half_size = Eigen::Vector2d(2.25, 0.9);
    body.yaw = yaw;
    body.z_min = ground + 0.25;
    body.z_max = ground + 1.0;
    body.material = Material::kCar;
    body.visible_from = from;
    body.visible_until = until;
    world.boxes.push_back(body);
    OrientedBox cabin = body;
    cabin.half_size = Eigen::Vector2d(1.2, 0.8);
    cabin.z_min = ground + 1.0;
    cabin.z_max = ground + 1.5;
    cabin.material = Material::kGlass;
    world.boxes.push_back(cabin);
}

void AddWall(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double thickness, double z_bottom, double z_top,
             Material material, World& world) {
    const Eigen::Vector2d mid = 0.5 * (a + b);
    const double ground = world.ground.Height(mid.x(), mid.y());
    OrientedBox wall;
    wall.center = mid;
    wall.half_size = Eigen::Vector2d(0.5 * (b - a).norm(), 0.5 * thickness);
    wall.yaw = Yaw(b - a);
    wall.z_min = ground + z_bottom;
    wall.z_max = ground + z_top;
    wall.material = material;
    world.boxes.push_back(wall);
}

void AddStandingBox(const Eigen::Vector2d& center, double yaw, const Eigen::Vector2d& half_size, double z_bottom,
                    double z_top, Material material, World& world) {
    const double ground = world.ground.Height(center.x(), center.y());
    OrientedBox box;
    box.center = center;
    box.half_size = half_size;
    box.yaw = yaw;
    box.z_min = ground + z_bottom;
    box.z_max = ground + z_top;
    box.material = material;
    world.boxes.push_back(box);
}

void AddMovingCars(int count, double min_speed, double max_speed, std::mt19937& rng, World& world) {
    for (int c = 0; c < count && !world.streets.edges.empty(); ++c) {
        const auto& edge = world.streets.edges[rng() % world.streets.edges.size()];
        MovingCar car;
        car.path = OffsetPolyline(edge.polyline, world.lane_offset);
        car.speed = Uniform(rng, min_speed, max_speed);
        car.phase = Uniform(rng, 0.0, 2.0 * edge.length);
        world.moving_cars.push_back(car);
    }
}

}  // namespace revisit
