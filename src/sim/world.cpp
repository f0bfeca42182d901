#include "sim/world.hpp"

#include <algorithm>
#include <cmath>

namespace revisit {

int StreetGraph::AddEdge(int a, int b, std::vector<Eigen::Vector2d> polyline) {
    Edge edge;
    edge.a = a;
    edge.b = b;
    edge.polyline = polyline.empty() ? std::vector<Eigen::Vector2d>{nodes[a], nodes[b]} : std::move(polyline);
    for (std::size_t i = 1; i < edge.polyline.size(); ++i) edge.length += (edge.polyline[i] - edge.polyline[i - 1]).norm();
    edges.push_back(std::move(edge));
    return static_cast<int>(edges.size()) - 1;
}

std::vector<std::vector<int>> StreetGraph::Adjacency() const {
    std::vector<std::vector<int>> adjacency(nodes.size());
    for (std::size_t e = 0; e < edges.size(); ++e) {
        adjacency[edges[e].a].push_back(static_cast<int>(e));
        adjacency[edges[e].b].push_back(static_cast<int>(e));
    }
    return adjacency;
}

OrientedBox MovingCar::BoxAt(double time, const Ground& ground) const {
    double total = 0.0;
    for (std::size_t i = 1; i < path.size(); ++i) total += (path[i] - path[i - 1]).norm();
    OrientedBox box;
    box.half_size = half_size;
    box.material = Material::kCar;
    if (path.size() < 2 || total <= 0.0) return box;
    // Back and forth: cycle of 2 * total; the return leg runs the path reversed.
    double s = std::fmod(phase + speed * time, 2.0 * total);
    if (s < 0.0) s += 2.0 * total;
    const bool returning = s > total;
    if (returning) s = 2.0 * total - s;
    std::size_t i = 1;
    double walked = 0.0;
    for (; i + 1 < path.size(); ++i) {
        const double step = (path[i] - path[i - 1]).norm();
        if (walked + step >= s) break;
        walked += step;
    }
    const Eigen::Vector2d d = path[i] - path[i - 1];
    const double step = std::max(d.norm(), 1e-9);
    const Eigen::Vector2d along = d / step;
    // The return leg uses the other lane: shift left of the forward direction by 4 m.
    const Eigen::Vector2d left(-along.y(), along.x());
    box.center = path[i - 1] + along * std::min(s - walked, step) + (returning ? 4.0 : 0.0) * left;
    box.yaw = std::atan2(along.y(), along.x());
    const double z = ground.Height(box.center.x(), box.center.y());
    box.z_min = z + 0.25;
    box.z_max = z + height;
    return box;
}

double PolylineLength(const std::vector<Eigen::Vector2d>& polyline) {
    double length = 0.0;
    for (std::size_t i = 1; i < polyline.size(); ++i) length += (polyline[i] - polyline[i - 1]).norm();
    return length;
}

Eigen::Vector2d PolylinePoint(const std::vector<Eigen::Vector2d>& polyline, double s, Eigen::Vector2d* tangent) {
    if (polyline.size() < 2) {
        if (tangent) *tangent = Eigen::Vector2d::UnitX();
        return polyline.empty() ? Eigen::Vector2d::Zero() : polyline.front();
    }
    double walked = 0.0;
    for (std::size_t i = 1; i < polyline.size(); ++i) {
        const Eigen::Vector2d d = polyline[i] - polyline[i - 1];
        const double step = d.norm();
        if (step < 1e-12) continue;
        if (walked + step >= s || i + 1 == polyline.size()) {
            if (tangent) *tangent = d / step;
            return polyline[i - 1] + d * std::clamp((s - walked) / step, 0.0, 1.0);
        }
        walked += step;
    }
    if (tangent) *tangent = Eigen::Vector2d::UnitX();
    return polyline.back();
}

std::vector<Eigen::Vector2d> OffsetPolyline(const std::vector<Eigen::Vector2d>& polyline, double right_offset) {
    std::vector<Eigen::Vector2d> out(polyline.size());
    auto right_of = [](const Eigen::Vector2d& d) { return Eigen::Vector2d(d.y(), -d.x()).normalized(); };
    for (std::size_t i = 0; i < polyline.size(); ++i) {
        Eigen::Vector2d normal = Eigen::Vector2d::Zero();
        if (i > 0) normal += right_of(polyline[i] - polyline[i - 1]);
        if (i + 1 < polyline.size()) normal += right_of(polyline[i + 1] - polyline[i]);
        const double n = normal.norm();
        // Mitre at bends: scale so the offset lines stay parallel to both segments.
        normal = n > 1e-9 ? Eigen::Vector2d(normal / n) : Eigen::Vector2d::Zero();
        double scale = 1.0;
        if (i > 0 && i + 1 < polyline.size()) scale = 1.0 / std::max(0.5, normal.dot(right_of(polyline[i] - polyline[i - 1])));
        out[i] = polyline[i] + normal * right_offset * scale;
    }
    return out;
}

}  // namespace revisit
