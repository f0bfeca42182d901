#pragma once
/// Street furniture and buildings as unions of primitives, standing on the world's ground.
/// Shared by the city, highway, indoor and around-trajectory generators.
#include <Eigen/Core>
#include <functional>
#include <random>
#include <vector>

#include "sim/world.hpp"

namespace revisit {

/// Building footprint along a street: `front_center` is the middle of the street-side facade,
/// `along` the unit direction of the street, the building extends away from the street by `depth`.
struct BuildingSpec {
    Eigen::Vector2d front_center = Eigen::Vector2d::Zero();  ///< [m]
    Eigen::Vector2d along{1.0, 0.0};                         ///< unit
    Eigen::Vector2d away{0.0, 1.0};                          ///< unit, from the street into the block
    double width = 20.0;                                     ///< [m] along the street
    double depth = 15.0;                                     ///< [m] away from the street
    double height = 15.0;                                    ///< [m]
};

/// Adds a building of random shape (rectangle, L, U, stepped) with facade protrusions and recesses,
/// so that bird's-eye density images have corners (METHOD.md section 3).
void AddBuilding(const BuildingSpec& spec, std::mt19937& rng, World& world);
/// Lamp post with an arm and a head; `away` points from the kerb to the road.
void AddLamp(const Eigen::Vector2d& base, const Eigen::Vector2d& towards_road, std::mt19937& rng, World& world);
/// Trunk plus one or two crown spheres.
void AddTree(const Eigen::Vector2d& base, std::mt19937& rng, World& world);
/// A bush: two or three overlapping foliage spheres low over the ground (rays scatter in them).
void AddBush(const Eigen::Vector2d& base, std::mt19937& rng, World& world);
/// A hedge from a to b: foliage spheres every ~0.8 m, 1-2 m high.
void AddHedge(const Eigen::Vector2d& a, const Eigen::Vector2d& b, std::mt19937& rng, World& world);
/// A sign post, bollard or bin: the small, scattered vertical structure of a real roadside.
void AddSmallFurniture(const Eigen::Vector2d& base, const Eigen::Vector2d& along, std::mt19937& rng, World& world);
/// Roadside clutter along one side of `line` (arc length s0..s1): bushes, hedges, signs, bollards and
/// bins between `near` and `far` [m] to the right (negative: left) of it, one every `spacing` [m] on
/// average. `accept` may veto a placement (returns false to take it back).
void AddRoadsideClutter(const std::vector<Eigen::Vector2d>& line, double s0, double s1, double near, double far,
                        double spacing, std::mt19937& rng, World& world,
                        const std::function<bool(std::size_t, std::size_t, std::size_t)>& accept = {});
/// `count` cars driving the lanes of random street edges at speeds in [min_speed, max_speed] [m/s].
void AddMovingCars(int count, double min_speed, double max_speed, std::mt19937& rng, World& world);
/// Parked car box; present only between `from` and `until` [s].
void AddParkedCar(const Eigen::Vector2d& center, double yaw, float from, float until, World& world);
/// Thin wall (fence, guard rail, room wall) from a to b.
void AddWall(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double thickness, double z_bottom, double z_top,
             Material material, World& world);
/// A box standing on the ground (furniture, sign panel, kiosk).
void AddStandingBox(const Eigen::Vector2d& center, double yaw, const Eigen::Vector2d& half_size, double z_bottom,
                    double z_top, Material material, World& world);

}  // namespace revisit
