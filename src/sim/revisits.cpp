#include "sim/revisits.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_map>

namespace revisit {

std::vector<Revisit> FindRevisits(const Poses& poses, const RevisitConfig& config) {
    const auto travelled = CumulativeDistance(poses);
    // Hash grid of positions with cells of `radius`: neighbours are in the 27 surrounding cells.
    auto key = [&](const Eigen::Vector3d& p) {
        const auto c = (p / config.radius).array().floor().cast<long long>();
        return (c.x() * 73856093LL) ^ (c.y() * 19349663LL) ^ (c.z() * 83492791LL);
    };
    std::unordered_multimap<long long, std::size_t> grid;
    std::vector<long> reference(poses.size(), -1);
    std::vector<double> distance(poses.size(), std::numeric_limits<double>::infinity());
    std::size_t inserted = 0;
    for (std::size_t i = 0; i < poses.size(); ++i) {
        // Poses enter the grid once they are min_gap behind the current one.
        while (inserted < i && travelled[inserted] < travelled[i] - config.min_gap) {
            grid.emplace(key(poses[inserted].translation()), inserted);
            ++inserted;
        }
        const Eigen::Vector3d p = poses[i].translation();
        for (int dx = -1; dx <= 1; ++dx)
            for (int dy = -1; dy <= 1; ++dy)
                for (int dz = -1; dz <= 1; ++dz) {
                    const auto range = grid.equal_range(key(p + config.radius * Eigen::Vector3d(dx, dy, dz)));
                    for (auto it = range.first; it != range.second; ++it) {
                        const double d = (poses[it->second].translation() - p).norm();
                        if (d < config.radius && d < distance[i]) distance[i] = d, reference[i] = static_cast<long>(it->second);
                    }
                }
    }
    // A return is a run of poses with an earlier neighbour and the same sense of travel relative to it.
    // Headings in the horizontal plane: a tilted handheld sensor's x axis points partly down.
    auto heading = [&](std::size_t i) {
        const Eigen::Vector2d x = poses[i].linear().col(0).head<2>();
        return x.norm() > 1e-6 ? Eigen::Vector2d(x.normalized()) : Eigen::Vector2d::UnitX();
    };
    auto heading_difference = [&](std::size_t i) {
        return std::acos(std::clamp(heading(i).dot(heading(static_cast<std::size_t>(reference[i]))), -1.0, 1.0));
    };
    std::vector<Revisit> revisits;
    for (std::size_t i = 0; i < poses.size();) {
        if (reference[i] < 0) {
            ++i;
            continue;
        }
        const bool opposite = heading_difference(i) > config.opposite_angle;
        std::size_t j = i, closest = i;
        while (j + 1 < poses.size() && reference[j + 1] >= 0 && (heading_difference(j + 1) > config.opposite_angle) == opposite) {
            ++j;
            if (distance[j] < distance[closest]) closest = j;
        }
        if (travelled[j] - travelled[i] >= config.min_length) {
            Revisit r;
            r.first = i;
            r.last = j;
            r.reference = static_cast<std::size_t>(reference[closest]);
            r.min_distance = distance[closest];
            // Mid-run heading: the closest pair often sits in a junction, where the headings turn.
            r.heading_difference = heading_difference((i + j) / 2);
            r.opposite = opposite;
            revisits.push_back(r);
        }
        i = j + 1;
    }
    return revisits;
}

}  // namespace revisit
