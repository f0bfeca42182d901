#include "evaluation/closure_truth.hpp"

#include "core/error.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <set>
#include <unordered_map>

namespace revisit {

ClosureAnchor AnchorOf(const MapClosureForEval& c, const Poses& T_odom_sensor) {
    if (c.query_first_scan > c.query_last_scan || c.ref_first_scan > c.ref_last_scan || c.query_last_scan >= T_odom_sensor.size() ||
        c.ref_last_scan >= T_odom_sensor.size())
        throw ConfigError("map closure scans " + std::to_string(c.query_first_scan) + ".." + std::to_string(c.query_last_scan) + " / " +
                          std::to_string(c.ref_first_scan) + ".." + std::to_string(c.ref_last_scan) + " outside the " +
                          std::to_string(T_odom_sensor.size()) + " odometry poses");
    // Every scan of both maps in the query map's frame: the query's by the odometry within it, the
    // reference's by the odometry within the reference map, then the closure.
    const Eigen::Isometry3d T_query_odom = T_odom_sensor[c.query_first_scan].inverse();
    const Eigen::Isometry3d T_query_odomref = c.T_query_ref * T_odom_sensor[c.ref_first_scan].inverse();
    ClosureAnchor anchor{c.query_first_scan, c.ref_first_scan, {}};
    double best = std::numeric_limits<double>::infinity();
    std::vector<Eigen::Vector3d> ref_positions;
    for (std::size_t r = c.ref_first_scan; r <= c.ref_last_scan; ++r)
        ref_positions.push_back((T_query_odomref * T_odom_sensor[r]).translation());
    for (std::size_t q = c.query_first_scan; q <= c.query_last_scan; ++q) {
        const Eigen::Vector3d query_position = (T_query_odom * T_odom_sensor[q]).translation();
        for (std::size_t k = 0; k < ref_positions.size(); ++k) {
            const double squared = (query_position - ref_positions[k]).squaredNorm();
            if (squared < best) {
                best = squared;
                anchor.query_scan = q;
                anchor.ref_scan = c.ref_first_scan + k;
            }
        }
    }
    anchor.T_query_scan_ref_scan = (T_query_odom * T_odom_sensor[anchor.query_scan]).inverse() * T_query_odomref *
                                   T_odom_sensor[anchor.ref_scan];
    return anchor;
}

ClosureTruth JudgeClosures(const std::vector<MapClosureForEval>& closures, const Poses& T_world_reference,
                           const ClosureTruthConfig& config, const Poses& T_odom_sensor) {
    ClosureTruth truth;
    for (const auto& c : closures) {
        ClosureVerdict verdict;
        verdict.first_scan_error = ClosureErrorAgainst(T_world_reference, c.query_first_scan, c.ref_first_scan, c.T_query_ref);
        verdict.error = verdict.first_scan_error;
        verdict.query_scan = c.query_first_scan;
        verdict.ref_scan = c.ref_first_scan;
        if (!T_odom_sensor.empty()) {
            // Within each map the closure's pose carries the odometry's error from where the maps
            // overlap to the map's first scan: judged there it would score the odometry, not the closure.
            const ClosureAnchor anchor = AnchorOf(c, T_odom_sensor);
            verdict.query_scan = anchor.query_scan;
            verdict.ref_scan = anchor.ref_scan;
            verdict.error = ClosureErrorAgainst(T_world_reference, anchor.query_scan, anchor.ref_scan, anchor.T_query_scan_ref_scan);
        }
        verdict.is_true = verdict.error.translation <= config.true_translation && verdict.error.yaw_deg <= config.true_rotation_deg;
        (verdict.is_true ? truth.num_true : truth.num_false)++;
        truth.verdicts.push_back(verdict);
    }
    return truth;
}

std::vector<std::vector<std::size_t>> FindRevisits(const Poses& T_world_reference, double radius, double gap) {
    const std::size_t n = T_world_reference.size();
    std::vector<double> travel(n, 0.0);
    for (std::size_t i = 1; i < n; ++i)
        travel[i] = travel[i - 1] + (T_world_reference[i].translation() - T_world_reference[i - 1].translation()).norm();
    // Planar grid of `radius` cells: a scan's neighbours within the radius are in the 3 x 3 cells around it.
    auto cell_of = [&](std::size_t i) {
        const Eigen::Vector3d p = T_world_reference[i].translation();
        return std::make_pair(std::int64_t(std::floor(p.x() / radius)), std::int64_t(std::floor(p.y() / radius)));
    };
    auto key = [](std::int64_t x, std::int64_t y) { return (std::uint64_t(x) << 32) ^ (std::uint64_t(y) & 0xffffffffu); };
    std::unordered_map<std::uint64_t, std::vector<std::size_t>> grid;
    std::vector<std::vector<std::size_t>> revisits(n);
    if (radius <= 0.0) return revisits;
    for (std::size_t i = 0; i < n; ++i) {
        const auto [cx, cy] = cell_of(i);
        for (std::int64_t dx = -1; dx <= 1; ++dx) {
            for (std::int64_t dy = -1; dy <= 1; ++dy) {
                const auto it = grid.find(key(cx + dx, cy + dy));
                if (it == grid.end()) continue;
                for (std::size_t e : it->second) {
                    if (travel[i] - travel[e] < gap) continue;
                    if ((T_world_reference[i].translation() - T_world_reference[e].translation()).norm() <= radius)
                        revisits[i].push_back(e);
                }
            }
        }
        std::sort(revisits[i].begin(), revisits[i].end());
        grid[key(cx, cy)].push_back(i);
    }
    return revisits;
}

RevisitCoverage ComputeRevisitCoverage(const std::vector<std::vector<std::size_t>>& revisits, const std::vector<MapRange>& maps,
                                       const std::vector<std::pair<std::size_t, std::size_t>>& true_map_pairs) {
    std::set<std::pair<std::size_t, std::size_t>> joined;
    for (const auto& [a, b] : true_map_pairs) joined.insert(std::minmax(a, b));
    RevisitCoverage coverage;
    for (std::size_t s = 0; s < revisits.size(); ++s) {
        if (revisits[s].empty()) continue;
        ++coverage.revisit_scans;
        const std::size_t map = MapIndexOfScan(maps, s);
        bool covered = false;
        for (std::size_t e : revisits[s]) {
            const std::size_t other = MapIndexOfScan(maps, e);
            covered = covered || (map < maps.size() && other < maps.size() && joined.count(std::minmax(map, other)) > 0);
        }
        coverage.covered_scans += covered ? 1 : 0;
    }
    if (coverage.revisit_scans > 0) coverage.coverage = double(coverage.covered_scans) / double(coverage.revisit_scans);
    return coverage;
}

}  // namespace revisit
