#include "pipeline/scan_trail.hpp"

namespace revisit {

ScanTrail MakeScanTrail(const std::vector<Eigen::Isometry3d>& T_map_scan, double travel_start) {
    ScanTrail trail;
    double along = travel_start;
    for (const auto& T : T_map_scan) {
        if (!trail.positions_in_map.empty()) along += (T.translation() - trail.positions_in_map.back()).norm();
        trail.positions_in_map.push_back(T.translation());
        trail.travel.push_back(along);
    }
    return trail;
}

bool TrailRevisits(const ScanTrail& earlier, const Eigen::Isometry3d& T_world_earlier, const ScanTrail& later,
                   const Eigen::Isometry3d& T_world_later, double radius, double gap) {
    const double radius_squared = radius * radius;
    std::vector<Eigen::Vector3d> earlier_in_world(earlier.positions_in_map.size());
    for (std::size_t i = 0; i < earlier_in_world.size(); ++i) earlier_in_world[i] = T_world_earlier * earlier.positions_in_map[i];
    for (std::size_t j = 0; j < later.positions_in_map.size() && j < later.travel.size(); ++j) {
        const Eigen::Vector3d p = T_world_later * later.positions_in_map[j];
        // Travel grows along the earlier trail: the scans far enough back come first.
        for (std::size_t i = 0; i < earlier_in_world.size() && i < earlier.travel.size() && later.travel[j] - earlier.travel[i] >= gap; ++i)
            if ((earlier_in_world[i] - p).squaredNorm() <= radius_squared) return true;
    }
    return false;
}

}  // namespace revisit
