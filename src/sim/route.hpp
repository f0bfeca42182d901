#pragma once
/// Routes through a street graph with a requested number of revisits, and the vehicle
/// (or handheld) motion along them at the sensor rate.
#include <cstdint>
#include <vector>

#include "core/trajectory.hpp"
#include "sim/drive.hpp"
#include "sim/world.hpp"

namespace revisit {

struct RouteConfig {
    double length = 3000.0;            ///< [m] route length: it ends at the first node beyond it, once all revisits are done
    int revisits = 6;                  ///< planned returns to streets driven earlier
    double opposite_fraction = 0.34;   ///< share of the planned revisits driven in the opposite direction
    int parallel_revisits = 1;         ///< extra returns along a new street parallel to one driven before (~1 block away)
    double min_revisit_gap = 300.0;    ///< [m] travelled before a street may be revisited on purpose
    double revisit_penalty = 4.0;      ///< exploration cost multiplier per earlier visit of a street
    double explore_radius = 350.0;     ///< [m] exploration targets lie at most this far (straight line)
    double corner_radius = 6.0;        ///< [m] corner rounding of the driven path (indoor: ~1 m)
    int start_node = -1;               ///< -1: the node nearest to the centre of the graph
};

/// Node sequence (consecutive nodes share an edge, no U-turns) with the requested revisits.
std::vector<int> PlanRoute(const StreetGraph& graph, const RouteConfig& config, std::uint64_t seed);

/// Centre-line polyline of a node sequence, moved `lane_offset` [m] to the right and resampled
/// every `spacing` [m], corners rounded over about `corner_radius` [m].
std::vector<Eigen::Vector2d> RoutePath(const StreetGraph& graph, const std::vector<int>& nodes, double lane_offset,
                                       double corner_radius = 6.0, double spacing = 1.0);

}  // namespace revisit
