#pragma once
/// A simulated world: static primitives, a ground height field, a street graph to drive on,
/// and moving cars. Plain data; generators fill it, the ray caster reads it.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "sim/primitives.hpp"

namespace revisit {

/// Streets (or corridors) as a graph: routes are planned on it.
struct StreetGraph {
    struct Edge {
        int a = 0;                               ///< node index at the start of `polyline`
        int b = 0;                               ///< node index at its end
        std::vector<Eigen::Vector2d> polyline;   ///< [m] centre line from node a to node b
        double length = 0.0;                     ///< [m] along the polyline
    };
    std::vector<Eigen::Vector2d> nodes;          ///< [m]
    std::vector<Edge> edges;
    std::vector<double> roundabout_radius;       ///< [m] per node: ring centre-line radius, 0 = plain junction (may be empty)

    double RoundaboutRadius(int node) const {
        return node < static_cast<int>(roundabout_radius.size()) ? roundabout_radius[node] : 0.0;
    }

    /// Adds an edge with a straight or given centre line and computes its length; returns its index.
    int AddEdge(int a, int b, std::vector<Eigen::Vector2d> polyline = {});
    /// Edges touching each node (indices into `edges`).
    std::vector<std::vector<int>> Adjacency() const;
};

/// A car driving back and forth along a polyline in its right-hand lane.
struct MovingCar {
    std::vector<Eigen::Vector2d> path;  ///< [m] lane centre line
    double speed = 10.0;                ///< [m/s]
    double phase = 0.0;                 ///< [m] position along the back-and-forth cycle at t = 0
    Eigen::Vector2d half_size{2.2, 0.9};
    double height = 1.5;                ///< [m]

    /// The car's box at time t [s] (ground height taken from `ground`).
    OrientedBox BoxAt(double time, const Ground& ground) const;
};

struct RoadSegment {
    Eigen::Vector2d a = Eigen::Vector2d::Zero();  ///< [m]
    Eigen::Vector2d b = Eigen::Vector2d::Zero();  ///< [m]
    double half_width = 5.0;                      ///< [m] asphalt half width (intensity)
};

struct World {
    std::string kind;                   ///< "city", "highway", "indoor", "around_trajectory"
    Ground ground;
    bool has_ceiling = false;           ///< indoor: a flat ceiling at `ceiling_height`
    double ceiling_height = 3.0;        ///< [m]
    std::vector<OrientedBox> boxes;
    std::vector<Cylinder> cylinders;
    std::vector<Sphere> spheres;
    std::vector<MovingCar> moving_cars;
    std::vector<RoadSegment> roads;     ///< asphalt areas (lower reflectivity than the ground)
    StreetGraph streets;
    double lane_offset = 2.0;           ///< [m] to the right of a street's centre line where vehicles drive
    /// [m] mean free path of a ray in foliage (vegetation spheres: crowns, bushes): a ray enters a
    /// crown and returns from an exponentially distributed depth, or passes through when that is
    /// beyond the crown, so foliage scatters returns through its volume as real trees do. 0: solid.
    double foliage_free_path = 0.0;

    std::size_t NumPrimitives() const { return boxes.size() + cylinders.size() + spheres.size(); }
};

/// The polyline shifted sideways by `right_offset` [m] (negative: to the left), vertex normals averaged.
/// Point at arc length s [m] along a polyline (clamped to its ends), and the unit tangent there.
Eigen::Vector2d PolylinePoint(const std::vector<Eigen::Vector2d>& polyline, double s, Eigen::Vector2d* tangent = nullptr);
/// Total length [m].
double PolylineLength(const std::vector<Eigen::Vector2d>& polyline);

std::vector<Eigen::Vector2d> OffsetPolyline(const std::vector<Eigen::Vector2d>& polyline, double right_offset);

}  // namespace revisit
