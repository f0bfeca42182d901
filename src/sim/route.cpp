#include "sim/route.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>
#include <random>

namespace revisit {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kTwoPi = 6.283185307179586;

/// Shortest node path from `source` to `target`; the first step may not go to `forbidden_first`
/// (no U-turn where the previous leg ended) and `banned_edge` is never used.
std::vector<int> ShortestPath(const StreetGraph& graph, const std::vector<std::vector<int>>& adjacency,
                              const std::vector<double>& edge_cost, int source, int target, int forbidden_first,
                              int banned_edge) {
    std::vector<double> distance(graph.nodes.size(), kInf);
    std::vector<int> parent(graph.nodes.size(), -1);
    using Item = std::pair<double, int>;
    std::priority_queue<Item, std::vector<Item>, std::greater<Item>> open;
    distance[source] = 0.0;
    open.push({0.0, source});
    while (!open.empty()) {
        const auto [d, n] = open.top();
        open.pop();
        if (d > distance[n]) continue;
        if (n == target) break;
        for (int e : adjacency[n]) {
            if (e == banned_edge) continue;
            const int m = graph.edges[e].a == n ? graph.edges[e].b : graph.edges[e].a;
            if (n == source && m == forbidden_first) continue;
            const double candidate = d + edge_cost[e];
            if (candidate < distance[m]) {
                distance[m] = candidate;
                parent[m] = n;
                open.push({candidate, m});
            }
        }
    }
    if (distance[target] == kInf) return {};
    std::vector<int> path;
    for (int n = target; n != -1; n = parent[n]) path.push_back(n);
    std::reverse(path.begin(), path.end());
    return path;
}

/// The part of a polyline outside the circle (c, r), cut at the circle, at its start or its end.
std::vector<Eigen::Vector2d> TrimAtRadius(std::vector<Eigen::Vector2d> polyline, const Eigen::Vector2d& c, double r,
                                          bool at_start) {
    if (!at_start) std::reverse(polyline.begin(), polyline.end());
    std::size_t i = 0;
    while (i + 1 < polyline.size() && (polyline[i + 1] - c).norm() < r) ++i;
    if (i + 1 < polyline.size() && (polyline[i] - c).norm() < r) {
        // Bisection for the crossing on segment i.
        Eigen::Vector2d inside = polyline[i], outside = polyline[i + 1];
        for (int k = 0; k < 30; ++k) {
            const Eigen::Vector2d mid = 0.5 * (inside + outside);
            ((mid - c).norm() < r ? inside : outside) = mid;
        }
        polyline.erase(polyline.begin(), polyline.begin() + static_cast<long>(i));
        polyline.front() = outside;
    }
    if (!at_start) std::reverse(polyline.begin(), polyline.end());
    return polyline;
}

int EdgeBetween(const StreetGraph& graph, const std::vector<std::vector<int>>& adjacency, int a, int b) {
    for (int e : adjacency[a])
        if ((graph.edges[e].a == a && graph.edges[e].b == b) || (graph.edges[e].a == b && graph.edges[e].b == a)) return e;
    return -1;
}

}  // namespace

std::vector<int> PlanRoute(const StreetGraph& graph, const RouteConfig& config, std::uint64_t seed) {
    std::mt19937 rng(static_cast<std::uint32_t>(seed * 40503u + 7u));
    const auto adjacency = graph.Adjacency();
    if (graph.nodes.empty() || graph.edges.empty()) return {};
    int current = config.start_node;
    if (current < 0) {
        Eigen::Vector2d centre = Eigen::Vector2d::Zero();
        for (const auto& n : graph.nodes) centre += n;
        centre /= static_cast<double>(graph.nodes.size());
        double best = kInf;
        for (std::size_t n = 0; n < graph.nodes.size(); ++n)
            if (!adjacency[n].empty() && (graph.nodes[n] - centre).norm() < best)
                best = (graph.nodes[n] - centre).norm(), current = static_cast<int>(n);
    }
    struct Traversal { int edge; int from; double start; };
    std::vector<Traversal> driven;
    std::vector<int> visits(graph.edges.size(), 0);
    std::vector<int> node_visits(graph.nodes.size(), 0);
    std::vector<bool> revisited(graph.edges.size(), false);
    std::vector<int> route{current};
    double length = 0.0;
    int previous = -1;
    auto append = [&](const std::vector<int>& path) {
        for (std::size_t i = 1; i < path.size(); ++i) {
            const int e = EdgeBetween(graph, adjacency, path[i - 1], path[i]);
            driven.push_back({e, path[i - 1], length});
            length += graph.edges[e].length;
            ++visits[e];
            ++node_visits[path[i]];
            route.push_back(path[i]);
        }
        if (path.size() >= 2) previous = path[path.size() - 2];
        current = path.back();
    };
    auto costs = [&]() {
        std::vector<double> cost(graph.edges.size());
        for (std::size_t e = 0; e < cost.size(); ++e)
            cost[e] = graph.edges[e].length * (1.0 + config.revisit_penalty * visits[e]);
        return cost;
    };
    const int planned = config.revisits + config.parallel_revisits;
    const double segment = config.length / (planned + 1);
    int done = 0, opposite_done = 0, parallel_done = 0;
    std::vector<double> plain(graph.edges.size());
    for (std::size_t e = 0; e < plain.size(); ++e) plain[e] = graph.edges[e].length;
    // Drives to `entry` by the shortest way (never over `edge`, no U-turn) and then along `edge` to `exit`.
    auto drive_edge = [&](int entry, int exit, int edge) {
        auto path = current == entry ? std::vector<int>{current}
                                     : ShortestPath(graph, adjacency, plain, current, entry, previous, edge);
        if (path.empty() || (path.size() == 1 && previous == exit)) return false;
        path.push_back(exit);
        append(path);
        return true;
    };
    auto old_enough = [&](const Traversal& t) {
        return t.start + graph.edges[t.edge].length < length - config.min_revisit_gap;
    };
    // The route ends after `length` once every planned revisit is driven (or found impossible).
    for (int iteration = 0; iteration < 10000 && (length < config.length || done + parallel_done < planned);
         ++iteration) {
        const int k = done + parallel_done;
        const bool due = k < planned && length >= (k + 1) * segment;
        const bool parallel = due && parallel_done < config.parallel_revisits && (k % 3 == 2 || done >= config.revisits);
        if (parallel) {
            // A street never driven, parallel to one driven earlier and within about a block of it, same direction.
            int best_edge = -1, best_entry = -1, best_exit = -1;
            double best_distance = kInf;
            for (const auto& t : driven) {
                if (!old_enough(t)) continue;
                const auto& e = graph.edges[t.edge];
                const int to = e.a == t.from ? e.b : e.a;
                const Eigen::Vector2d dir = (graph.nodes[to] - graph.nodes[t.from]).normalized();
                const Eigen::Vector2d mid = 0.5 * (graph.nodes[to] + graph.nodes[t.from]);
                for (std::size_t c = 0; c < graph.edges.size(); ++c) {
                    if (visits[c] > 0) continue;
                    const auto& ce = graph.edges[c];
                    const Eigen::Vector2d cdir = (graph.nodes[ce.b] - graph.nodes[ce.a]).normalized();
                    const Eigen::Vector2d offset = 0.5 * (graph.nodes[ce.a] + graph.nodes[ce.b]) - mid;
                    const double lateral = std::abs(offset.x() * dir.y() - offset.y() * dir.x());
                    if (std::abs(cdir.dot(dir)) < 0.95 || lateral < 20.0 || offset.norm() > 1.5 * e.length) continue;
                    const int entry = cdir.dot(dir) > 0.0 ? ce.a : ce.b;
                    const double distance = (graph.nodes[entry] - graph.nodes[current]).norm();
                    if (distance < best_distance)
                        best_distance = distance, best_edge = static_cast<int>(c), best_entry = entry,
                        best_exit = entry == ce.a ? ce.b : ce.a;
                }
            }
            ++parallel_done;  // counted even when impossible, so the route always ends
            if (best_edge >= 0 && drive_edge(best_entry, best_exit, best_edge)) continue;
        } else if (due) {
            // A street driven long enough ago, entered again from the chosen end.
            std::vector<const Traversal*> candidates;
            for (const auto& t : driven)
                if (old_enough(t) && !revisited[t.edge]) candidates.push_back(&t);
            if (!candidates.empty()) {
                const bool opposite =
                    std::floor((done + 1) * config.opposite_fraction + 1e-9) > opposite_done;
                // One of the three streets whose entry is nearest: a short approach keeps revisits frequent.
                auto entry_of = [&](const Traversal* c) {
                    const auto& e = graph.edges[c->edge];
                    const int far_end = e.a == c->from ? e.b : e.a;
                    return (graph.nodes[opposite ? far_end : c->from] - graph.nodes[current]).norm();
                };
                std::sort(candidates.begin(), candidates.end(),
                          [&](const Traversal* x, const Traversal* y) { return entry_of(x) < entry_of(y); });
                const Traversal t = *candidates[rng() % std::min<std::size_t>(3, candidates.size())];  // copy: `driven` grows
                const int from = t.from;
                const int to = graph.edges[t.edge].a == from ? graph.edges[t.edge].b : graph.edges[t.edge].a;
                if (drive_edge(opposite ? to : from, opposite ? from : to, t.edge)) {
                    revisited[t.edge] = true;
                    ++done;
                    if (opposite) ++opposite_done;
                    continue;
                }
            }
        }
        // Explore: a random rarely visited node at most `explore_radius` away, reached preferring new streets.
        int target = -1;
        for (int k = 0; k < 24; ++k) {
            const int candidate = static_cast<int>(rng() % graph.nodes.size());
            if (candidate == current || adjacency[candidate].empty()) continue;
            if ((graph.nodes[candidate] - graph.nodes[current]).norm() > config.explore_radius) continue;
            if (target < 0 || node_visits[candidate] < node_visits[target]) target = candidate;
        }
        if (target < 0) {  // nothing that close (sparse graphs): a neighbour other than where we came from
            for (int e : adjacency[current]) {
                const int m = graph.edges[e].a == current ? graph.edges[e].b : graph.edges[e].a;
                if (m != previous && (target < 0 || rng() % 2 == 0)) target = m;
            }
            if (target < 0) continue;
        }
        const auto path = ShortestPath(graph, adjacency, costs(), current, target, previous, -1);
        if (path.size() >= 2) append(path);
    }
    return route;
}

std::vector<Eigen::Vector2d> RoutePath(const StreetGraph& graph, const std::vector<int>& nodes, double lane_offset,
                                       double corner_radius, double spacing) {
    const auto adjacency = graph.Adjacency();
    // Legs along the direction of travel.
    std::vector<std::vector<Eigen::Vector2d>> legs;
    std::vector<int> leg_end_node;
    for (std::size_t i = 1; i < nodes.size(); ++i) {
        const int e = EdgeBetween(graph, adjacency, nodes[i - 1], nodes[i]);
        if (e < 0) continue;
        auto polyline = graph.edges[e].polyline;
        if (graph.edges[e].a != nodes[i - 1]) std::reverse(polyline.begin(), polyline.end());
        legs.push_back(std::move(polyline));
        leg_end_node.push_back(nodes[i]);
    }
    // Roundabouts: cut both legs at the ring and drive counter-clockwise around it (right-hand traffic).
    std::vector<Eigen::Vector2d> centre;
    for (std::size_t k = 0; k < legs.size(); ++k) {
        auto leg = legs[k];
        const int start_node = k > 0 ? leg_end_node[k - 1] : -1;
        const double r_start = start_node >= 0 ? graph.RoundaboutRadius(start_node) : 0.0;
        if (r_start > 0.0 && !centre.empty()) {
            const Eigen::Vector2d c = graph.nodes[start_node];
            leg = TrimAtRadius(leg, c, r_start, /*at_start=*/true);
            const double a_in = std::atan2(centre.back().y() - c.y(), centre.back().x() - c.x());
            const double a_out = std::atan2(leg.front().y() - c.y(), leg.front().x() - c.x());
            double sweep = std::fmod(a_out - a_in + 4.0 * kTwoPi, kTwoPi);
            if (sweep < 0.2) sweep += kTwoPi;  // almost straight back: go all the way round
            const int steps = std::max(2, static_cast<int>(sweep * r_start / 1.0));
            for (int i = 1; i < steps; ++i) {
                const double a = a_in + sweep * i / steps;
                centre.push_back(c + r_start * Eigen::Vector2d(std::cos(a), std::sin(a)));
            }
        }
        if (k == 0 && graph.RoundaboutRadius(nodes.front()) > 0.0)  // start on the ring, not on the island
            leg = TrimAtRadius(leg, graph.nodes[nodes.front()], graph.RoundaboutRadius(nodes.front()), true);
        const double r_end = graph.RoundaboutRadius(leg_end_node[k]);
        if (r_end > 0.0) leg = TrimAtRadius(leg, graph.nodes[leg_end_node[k]], r_end, /*at_start=*/false);
        for (std::size_t i = centre.empty() ? 0 : (r_start > 0.0 ? 0 : 1); i < leg.size(); ++i) centre.push_back(leg[i]);
    }
    if (centre.size() < 2) return centre;
    const auto lane = OffsetPolyline(centre, lane_offset);
    // Resample, then round corners with a moving average over +-corner_radius.
    std::vector<Eigen::Vector2d> dense;
    for (std::size_t i = 1; i < lane.size(); ++i) {
        const Eigen::Vector2d d = lane[i] - lane[i - 1];
        const int steps = std::max(1, static_cast<int>(std::ceil(d.norm() / spacing)));
        for (int k = 0; k < steps; ++k) dense.push_back(lane[i - 1] + d * (static_cast<double>(k) / steps));
    }
    dense.push_back(lane.back());
    const int window = std::max(1, static_cast<int>(corner_radius / spacing));
    for (int pass = 0; pass < 2; ++pass) {
        std::vector<Eigen::Vector2d> smooth(dense.size());
        for (int i = 0; i < static_cast<int>(dense.size()); ++i) {
            const int w = std::min({window, i, static_cast<int>(dense.size()) - 1 - i});
            Eigen::Vector2d sum = Eigen::Vector2d::Zero();
            for (int k = -w; k <= w; ++k) sum += dense[i + k];
            smooth[i] = sum / (2 * w + 1);
        }
        dense.swap(smooth);
    }
    return dense;
}

}  // namespace revisit
