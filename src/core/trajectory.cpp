#include "core/trajectory.hpp"

namespace revisit {

std::vector<double> CumulativeDistance(const Poses& poses) {
    std::vector<double> distance(poses.size(), 0.0);
    for (std::size_t i = 1; i < poses.size(); ++i) {
        distance[i] = distance[i - 1] + (poses[i].translation() - poses[i - 1].translation()).norm();
    }
    return distance;
}

double PathLength(const Poses& poses) {
    return poses.empty() ? 0.0 : CumulativeDistance(poses).back();
}

}  // namespace revisit
