#pragma once
/// World generators, deterministic from a seed.
#include <cstdint>

#include "core/trajectory.hpp"
#include "sim/world.hpp"

namespace revisit {

/// A perturbed street grid with curved streets, buildings, lamps, trees, parked and moving cars.
struct CityConfig {
    int blocks_x = 6;                  ///< blocks along x
    int blocks_y = 6;                  ///< blocks along y
    double block_size = 110.0;         ///< [m] street spacing
    double node_jitter = 10.0;         ///< [m] random shift of each intersection
    double curved_fraction = 0.15;     ///< share of streets bent into an arc
    double curve_amplitude = 6.0;      ///< [m] lateral bend of curved streets
    double removed_fraction = 0.06;    ///< share of interior streets removed (irregular blocks)
    double roundabout_fraction = 0.12; ///< share of four-way junctions built as (mini) roundabouts
    double roundabout_radius = 7.0;    ///< [m] ring centre line; the island has half this radius
    double road_half_width = 6.0;      ///< [m]
    double sidewalk = 3.5;             ///< [m]
    double min_building_height = 5.0;  ///< [m]
    double max_building_height = 40.0; ///< [m]
    double lamp_spacing_min = 20.0;    ///< [m]
    double lamp_spacing_max = 40.0;    ///< [m]
    double tree_street_fraction = 0.4; ///< share of streets lined with trees
    double parked_car_density = 0.35;  ///< probability of a car per 6 m parking slot
    double transient_car_fraction = 0.4;  ///< parked cars present only for a while (differ between visits)
    double transient_horizon = 600.0;  ///< [s] time span over which transient cars come and go
    int moving_cars = 25;
    double fence_probability = 0.5;    ///< gaps between buildings closed by a fence or wall
    /// Also build along the outer side of the perimeter streets: a campus or a quarter lies within a
    /// town. Without it a view outward from a perimeter street is bare ground to the horizon, which no
    /// real place is (src/sim/README.md, "The worlds' outer streets"). Own random stream.
    bool outer_frontage = true;
    double ground_slope = 0.01;        ///< [m per m] overall tilt
    double ground_amplitude = 1.5;     ///< [m] undulation
    // What makes real streets registrable (issue 15, src/sim/README.md): none of it is needed for the
    // pictures, all of it for scan-to-map ICP to behave as on real scans.
    double ground_relief = 0.06;       ///< [m] metre-scale relief amplitude (slope varies every few metres)
    double ground_roughness = 0.02;    ///< [m] centimetre-scale roughness amplitude
    double foliage_free_path = 0.8;    ///< [m] rays penetrate crowns and bushes (0: solid spheres)
    double bush_spacing = 5.0;         ///< [m] mean gap between roadside clutter items (bushes, hedges, signs, bollards, bins) per street side (0: none)
};

/// Long roads with sparse structure: a ring road with two cross roads, guard rails, lamps, signs, trees.
struct HighwayConfig {
    double ring_radius = 700.0;        ///< [m]
    double radius_variation = 0.15;    ///< relative wobble of the ring
    double road_half_width = 7.5;      ///< [m]
    double lamp_spacing = 60.0;        ///< [m]
    double sign_spacing = 400.0;       ///< [m]
    double tree_probability = 0.15;    ///< per 25 m of road side
    double ground_amplitude = 3.0;     ///< [m]
    double ground_relief = 0.06;       ///< [m] metre-scale relief amplitude
    double ground_roughness = 0.02;    ///< [m] centimetre-scale roughness amplitude
    double foliage_free_path = 0.8;    ///< [m] rays penetrate crowns (0: solid)
    double bush_spacing = 6.0;         ///< [m] mean gap between verge clutter items (bushes, hedges, posts) per side (0: none)
    double rail_post_spacing = 2.0;    ///< [m] guard rail posts (0: none)
    // What makes a real highway registrable along the road (issue 15; KITTI 01): the verge changes.
    double bank_probability = 0.5;     ///< share of the verge (in 30-120 m sections) with an earth bank or cutting (0: none)
    double bank_height = 2.5;          ///< [m] mean height of a bank; it varies every 10 m
    double tree_belt_probability = 0.35;  ///< share of the verge (in 40-150 m sections) lined with a belt of trees
    double overpass_spacing = 1200.0;  ///< [m] mean spacing of bridges over the road (0: none)
    int moving_cars = 15;
};

/// Indoor floor or campus: corridors on a grid, rooms with doors and furniture, a ceiling.
struct IndoorConfig {
    int rooms_x = 5;
    int rooms_y = 4;
    double room_size = 9.0;            ///< [m] corridor spacing
    double corridor_half_width = 1.2;  ///< [m]
    double wall_height = 3.0;          ///< [m]
    double door_width = 1.0;           ///< [m]
    int furniture_per_room = 5;
    bool ceiling = true;
};

World GenerateCity(const CityConfig& config, std::uint64_t seed);
World GenerateHighway(const HighwayConfig& config, std::uint64_t seed);
World GenerateIndoor(const IndoorConfig& config, std::uint64_t seed);

/// Streets that follow a given trajectory (planar positions of `poses`, up axis guessed), buildings and
/// furniture along them but never within `clearance` [m] of the route. The street graph is the route.
struct AroundTrajectoryConfig {
    CityConfig city;                   ///< densities and sizes reused from the city generator
    double clearance = 6.0;            ///< [m] from the route to buildings, lamps and trees
    double near_clearance = 2.6;       ///< [m] from the route to parked cars (clutter: 1 m more)
    double parking_offset = 3.8;       ///< [m] from the route to the centre line of parked cars
    double sample_spacing = 5.0;       ///< [m] route resampling
};
World GenerateAroundTrajectory(const Poses& poses, const AroundTrajectoryConfig& config, std::uint64_t seed);

}  // namespace revisit
