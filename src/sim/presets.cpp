#include "sim/presets.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.hpp"

namespace revisit {
namespace {

constexpr double kDegree = 3.14159265358979323846 / 180.0;

SimConfig City(const std::string& name, SensorConfig sensor) {
    SimConfig config;
    config.name = name;
    config.world = WorldKind::kCity;
    config.sensor = std::move(sensor);
    config.route.length = 2500.0;
    config.route.revisits = 7;  // merged and junction returns aside, >= 5 distinct revisits for seeds 1-10
    config.route.min_revisit_gap = 250.0;
    config.motion.cruise_speed = 12.0;
    return config;
}

/// A small campus: narrow paths, low buildings, trees, no traffic; walked with a handheld sensor.
SimConfig Campus(const std::string& name, SensorConfig sensor) {
    SimConfig config;
    config.name = name;
    config.world = WorldKind::kCity;
    config.city.blocks_x = 3;
    config.city.blocks_y = 3;
    config.city.block_size = 45.0;
    config.city.node_jitter = 4.0;
    config.city.curve_amplitude = 3.0;
    config.city.road_half_width = 2.5;
    config.city.sidewalk = 1.0;
    config.city.min_building_height = 4.0;
    config.city.max_building_height = 15.0;
    config.city.lamp_spacing_min = 12.0;
    config.city.lamp_spacing_max = 20.0;
    config.city.tree_street_fraction = 0.6;
    config.city.parked_car_density = 0.0;
    config.city.moving_cars = 0;
    config.city.removed_fraction = 0.0;
    config.moving_cars = false;
    config.route.length = 300.0;
    config.route.revisits = 3;
    config.route.opposite_fraction = 0.5;
    config.route.min_revisit_gap = 60.0;
    config.route.explore_radius = 120.0;
    config.route.corner_radius = 2.0;
    config.motion.cruise_speed = 1.4;
    config.motion.start_speed = 1.0;
    config.motion.max_lateral_accel = 0.5;
    config.motion.handheld = true;
    config.motion.min_turn_radius = 0.0;  // walking: the path as given, no car steering limits
    config.motion.mount_height = 1.4;
    config.motion.mount_pitch = 20.0 * kDegree;  // held tilted towards the ground in front
    config.sensor = std::move(sensor);
    config.sensor.motion_distortion = true;
    config.odometry.speed_scale_bias = 0.02;
    return config;
}

SimConfig Indoor(const std::string& name, SensorConfig sensor) {
    SimConfig config;
    config.name = name;
    config.world = WorldKind::kIndoor;
    config.moving_cars = false;
    config.route.length = 300.0;
    config.route.revisits = 5;
    config.route.opposite_fraction = 0.4;
    config.route.min_revisit_gap = 40.0;
    config.route.corner_radius = 1.0;
    config.motion.cruise_speed = 1.0;
    config.motion.start_speed = 0.5;
    config.motion.max_lateral_accel = 0.5;
    config.motion.mount_height = 0.4;
    config.motion.min_turn_radius = 0.0;  // a robot turning on the spot in corridors, no car steering limits
    config.sensor = std::move(sensor);
    config.odometry.speed_scale_bias = 0.02;
    config.odometry.yaw_rate_bias = 0.005;
    return config;
}

}  // namespace

std::vector<std::string> SimPresetNames() {
    return {"demo",          "city-64",         "city-16",       "city-128",     "city-livox",
            "highway-64",    "campus-handheld", "campus-vlp16",  "campus-os0",   "indoor-2d-180", "indoor-2d-360",
            "indoor-depth",  "tiny"};
}

SimConfig SimPreset(const std::string& name) {
    if (name == "demo" || name == "city-64") return City(name, Hdl64Sensor());
    if (name == "city-16") return City(name, Vlp16Sensor());
    if (name == "city-128") return City(name, Os128Sensor());
    if (name == "city-livox") {
        SimConfig config = City(name, LivoxAviaSensor());
        config.sensor.motion_distortion = true;
        return config;
    }
    if (name == "highway-64") {
        SimConfig config;
        config.name = name;
        config.world = WorldKind::kHighway;
        config.sensor = Hdl64Sensor();
        config.route.length = 6000.0;
        config.route.revisits = 4;
        config.route.opposite_fraction = 0.5;
        config.route.min_revisit_gap = 1000.0;
        config.route.explore_radius = 2000.0;
        config.motion.cruise_speed = 25.0;
        config.motion.max_lateral_accel = 3.0;
        return config;
    }
    if (name == "campus-handheld") return Campus(name, LivoxAviaSensor());
    if (name == "campus-vlp16") return Campus(name, Vlp16Sensor());
    if (name == "campus-os0") {
        // A 360-degree head with a 90-degree vertical field carried upright: it needs no tilt to see the ground.
        SimConfig config = Campus(name, Os0Sensor());
        config.motion.mount_pitch = 0.0;
        return config;
    }
    if (name == "indoor-2d-180") return Indoor(name, PlanarLaserSensor(180.0));
    if (name == "indoor-2d-360") return Indoor(name, PlanarLaserSensor(360.0));
    if (name == "indoor-depth") {
        SimConfig config = Indoor(name, DepthCameraSensor());
        config.sensor.rate = 10.0;  // 300k points per frame: 10 Hz rather than 30 keeps sequences smaller
        config.motion.mount_height = 1.0;
        config.route.length = 60.0;
        config.route.revisits = 2;
        config.route.opposite_fraction = 0.5;
        return config;
    }
    if (name == "tiny") {
        // For tests and smoke runs: a 3x3 city, 16 beams, about 800 m with revisits.
        SimConfig config = City(name, Vlp16Sensor());
        config.city.blocks_x = 3;
        config.city.blocks_y = 3;
        config.city.moving_cars = 5;
        config.route.length = 900.0;
        config.route.revisits = 3;
        config.route.min_revisit_gap = 200.0;
        config.sensor.azimuth_steps = 900;
        return config;
    }
    std::string known;
    for (const auto& n : SimPresetNames()) known += (known.empty() ? "" : ", ") + n;
    throw ConfigError("sim.preset: unknown preset '" + name + "' (known: " + known + ")");
}

SimConfig AlongTrajectory(SimConfig config, const std::filesystem::path& trajectory_file) {
    config.world = WorldKind::kAroundTrajectory;
    config.trajectory_file = trajectory_file;
    config.around.city = config.city;
    return config;
}

SimConfig WithRouteLength(SimConfig config, double length) {
    if (!(length >= 100.0 && length <= 500000.0))
        throw ConfigError("sim: route length " + std::to_string(length) + " m is outside [100, 500000] m");
    if (config.world != WorldKind::kCity && config.world != WorldKind::kHighway)
        throw ConfigError("sim: a route length applies to the city and highway presets, not to '" + config.name + "'");
    const double ratio = length / config.route.length;
    config.route.length = length;
    // A city's revisits as often per kilometre as the preset plans them. A highway keeps its number:
    // its graph (a ring, two cross roads) has the same few streets at any size, and a revisit drives a
    // street not revisited before, so the longer route spaces the same revisits farther apart.
    if (config.world == WorldKind::kCity)
        config.route.revisits = std::max(1, static_cast<int>(std::lround(config.route.revisits * ratio)));
    if (ratio > 1.0) {
        // The area grows with the route (a grid's street length goes with its area), so the drive
        // keeps exploring instead of circling the preset's few blocks.
        const double grow = std::sqrt(ratio);
        config.route.explore_radius *= grow;
        config.route.min_revisit_gap *= grow;
        if (config.world == WorldKind::kCity) {
            config.city.blocks_x = static_cast<int>(std::ceil(config.city.blocks_x * grow));
            config.city.blocks_y = static_cast<int>(std::ceil(config.city.blocks_y * grow));
            config.city.moving_cars = static_cast<int>(std::lround(config.city.moving_cars * ratio));
        } else {
            // A ring road and two cross roads hold about 10 radii of road; the route drives most of it twice.
            config.highway.ring_radius = std::max(config.highway.ring_radius, length / 20.0);
            config.route.explore_radius = std::max(config.route.explore_radius, 3.0 * config.highway.ring_radius);
            config.highway.moving_cars = static_cast<int>(std::lround(config.highway.moving_cars * grow));
        }
    }
    return config;
}

}  // namespace revisit
