#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "sim/generators.hpp"
#include "sim/ray_caster.hpp"

namespace revisit {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

World BoxWorld() {
    World world;
    OrientedBox box;
    box.center = Eigen::Vector2d(11.0, 0.0);
    box.half_size = Eigen::Vector2d(1.0, 2.0);
    box.z_min = 0.0;
    box.z_max = 3.0;
    world.boxes.push_back(box);
    return world;
}

TEST(RayCaster, BeamAgainstKnownBoxReturnsExactRange) {
    const World world = BoxWorld();
    const RayCaster caster(world);
    const RayHit hit = caster.Cast(Eigen::Vector3d(0.0, 0.0, 1.0), Eigen::Vector3d::UnitX(), 0.5, 100.0);
    ASSERT_TRUE(hit.hit());
    EXPECT_NEAR(hit.range, 10.0, 1e-9);
    EXPECT_EQ(hit.material, Material::kBuilding);
    // A slanted beam: 10 m along x, 0.5 m up at the face.
    const Eigen::Vector3d direction = Eigen::Vector3d(10.0, 1.0, 0.5).normalized();
    EXPECT_NEAR(caster.Cast(Eigen::Vector3d(0.0, 0.0, 1.0), direction, 0.5, 100.0).range,
                Eigen::Vector3d(10.0, 1.0, 0.5).norm(), 1e-9);
    // Passing above the box the beam meets the flat ground far away: z = 1 - 0.05 t = 0 at t = 20 m (slope).
    const Eigen::Vector3d down = Eigen::Vector3d(1.0, 0.0, -0.05).normalized();
    EXPECT_NEAR(caster.Cast(Eigen::Vector3d(0.0, 0.0, 4.0), down, 0.5, 200.0).range, 80.0 / down.x() * 1.0, 1e-2);
    // Beside the box nothing but the sky.
    EXPECT_FALSE(caster.Cast(Eigen::Vector3d(0.0, 0.0, 1.0), Eigen::Vector3d::UnitY(), 0.5, 100.0).hit());
}

TEST(RayCaster, RotatedBoxCylinderSphereAndGround) {
    World world;
    OrientedBox diamond;  // a 2x2 box turned 45 degrees: its corner points at the sensor
    diamond.center = Eigen::Vector2d(10.0, 0.0);
    diamond.half_size = Eigen::Vector2d(1.0, 1.0);
    diamond.yaw = M_PI / 4;
    diamond.z_max = 5.0;
    world.boxes.push_back(diamond);
    world.cylinders.push_back({Eigen::Vector2d(0.0, 10.0), 0.5, 0.0, 5.0, Material::kMetal});
    world.spheres.push_back({Eigen::Vector3d(-10.0, 0.0, 2.0), 1.5, Material::kVegetation});
    const RayCaster caster(world);
    const Eigen::Vector3d origin(0.0, 0.0, 2.0);
    EXPECT_NEAR(caster.Cast(origin, Eigen::Vector3d::UnitX(), 0.1, 50.0).range, 10.0 - std::sqrt(2.0), 1e-9);
    const RayHit pole = caster.Cast(origin, Eigen::Vector3d::UnitY(), 0.1, 50.0);
    EXPECT_NEAR(pole.range, 9.5, 1e-9);
    EXPECT_EQ(pole.material, Material::kMetal);
    EXPECT_NEAR(caster.Cast(origin, -Eigen::Vector3d::UnitX(), 0.1, 50.0).range, 8.5, 1e-9);
    const Eigen::Vector3d down45 = Eigen::Vector3d(0.0, -1.0, -1.0).normalized();
    EXPECT_NEAR(caster.Cast(origin, down45, 0.1, 50.0).range, 2.0 * std::sqrt(2.0), 1e-3);
    // min_range: a return closer than the minimum is skipped, the next surface is reported.
    EXPECT_FALSE(caster.Cast(origin, Eigen::Vector3d::UnitX(), 0.1, 5.0).hit());
}

TEST(RayCaster, ParkedCarsExistOnlyInTheirTimeWindow) {
    World world = BoxWorld();
    world.boxes[0].visible_from = 100.0f;
    world.boxes[0].visible_until = 200.0f;
    const RayCaster caster(world);
    const Eigen::Vector3d origin(0.0, 0.0, 1.0);
    EXPECT_FALSE(caster.Cast(origin, Eigen::Vector3d::UnitX(), 0.5, 50.0, 50.0).hit());
    EXPECT_NEAR(caster.Cast(origin, Eigen::Vector3d::UnitX(), 0.5, 50.0, 150.0).range, 10.0, 1e-9);
    EXPECT_FALSE(caster.Cast(origin, Eigen::Vector3d::UnitX(), 0.5, 50.0, 250.0).hit());
}

/// The grid must return exactly what testing every primitive would (ground: raster vs exact, 1 cm).
TEST(RayCaster, GridMatchesBruteForceInACity) {
    CityConfig config;
    config.blocks_x = 3;
    config.blocks_y = 3;
    // Solid crowns and the smooth ground: the brute force below knows only exact surfaces.
    config.foliage_free_path = config.ground_relief = config.ground_roughness = 0.0;
    const World world = GenerateCity(config, 5);
    const RayCaster caster(world);
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> position(0.0, 330.0), unit(-1.0, 1.0);
    int hits = 0;
    for (int i = 0; i < 4000; ++i) {
        const Eigen::Vector2d xy(position(rng), position(rng));
        const Eigen::Vector3d origin(xy.x(), xy.y(), world.ground.Height(xy.x(), xy.y()) + 1.8);
        const Eigen::Vector3d direction = Eigen::Vector3d(unit(rng), unit(rng), 0.3 * unit(rng)).normalized();
        double best = std::min(120.0, IntersectGround(world.ground, origin, direction, 0.5, 120.0));
        bool inside = false;
        for (const auto& box : world.boxes) {
            if (box.visible_from > 0.0f || box.visible_until < 0.0f) continue;  // parked elsewhere at time 0
            const double t = IntersectBox(box, origin, direction, 0.5, best);
            best = std::min(best, t);
            const Eigen::Vector4d b = BoundsXY(box);
            inside |= xy.x() > b.x() && xy.x() < b.z() && xy.y() > b.y() && xy.y() < b.w();
        }
        if (inside) continue;  // origins inside an object's bounds are not sensor positions
        for (const auto& c : world.cylinders) best = std::min(best, IntersectCylinder(c, origin, direction, 0.5, best));
        for (const auto& s : world.spheres) best = std::min(best, IntersectSphere(s, origin, direction, 0.5, best));
        const RayHit hit = caster.Cast(origin, direction, 0.5, 120.0);
        if (best >= 120.0) {
            EXPECT_FALSE(hit.hit()) << "ray " << i;
        } else {
            ASSERT_TRUE(hit.hit()) << "ray " << i;
            EXPECT_NEAR(hit.range, best, 1e-2) << "ray " << i;
            ++hits;
        }
    }
    EXPECT_GT(hits, 2000);
}

TEST(RayCaster, FoliageScattersReturnsThroughItsVolume) {
    World world;
    world.foliage_free_path = 0.8;
    world.spheres.push_back({Eigen::Vector3d(10.0, 0.0, 2.0), 2.0, Material::kVegetation});
    world.boxes.push_back({Eigen::Vector2d(30.0, 0.0), Eigen::Vector2d(0.5, 30.0), 0.0, -1.0, 10.0, Material::kWall});
    const RayCaster caster(world);
    int in_crown = 0, through = 0;
    double deepest = 0.0;
    for (std::uint64_t key = 0; key < 2000; ++key) {
        const RayHit hit = caster.Cast(Eigen::Vector3d(0, 0, 2.0), Eigen::Vector3d::UnitX(), 0.5, 100.0, 0.0, {}, key);
        ASSERT_TRUE(hit.hit());
        if (hit.material == Material::kVegetation) {
            ASSERT_GE(hit.range, 8.0);
            ASSERT_LE(hit.range, 12.0);
            deepest = std::max(deepest, hit.range);
            ++in_crown;
        } else {
            EXPECT_NEAR(hit.range, 29.5, 1e-9);
            ++through;
        }
    }
    // 4 m of foliage at a 0.8 m free path: exp(-5) = 0.7% pass through; returns spread over metres.
    EXPECT_GT(in_crown, 1900);
    EXPECT_GT(through, 2);
    EXPECT_GT(deepest, 10.5);
}

}  // namespace
}  // namespace revisit
