#include "pipeline/free_space_gate.hpp"

#include <algorithm>
#include <cstdio>

namespace revisit {

FreeSpaceGate::FreeSpaceGate(const PipelineConfig& config)
    : active_(config.odometry.planar && config.refinement.min_free_space_agreement > 0.0),
      overlap_explicit_(config.explicit_keys.count("refinement.min_overlap") != 0),
      cell_(config.output.map_voxel),
      min_agreement_(config.refinement.min_free_space_agreement),
      min_observed_(config.refinement.min_correspondences) {}

void FreeSpaceGate::AddScan(std::size_t scan_index, const Eigen::Vector3f* points_in_sensor, std::size_t count,
                            const Eigen::Isometry3d& T_world_sensor) {
    if (active_) open_scans_.push_back({scan_index, {points_in_sensor, points_in_sensor + count}, T_world_sensor});
}

void FreeSpaceGate::CloseMap(const LocalMap& map) {
    if (!active_) return;
    std::vector<std::vector<Eigen::Vector3f>> scans;
    std::vector<Eigen::Isometry3d> T_map_scan;
    const Eigen::Isometry3d T_map_world = map.T_world_map.inverse();
    auto kept = open_scans_.begin();
    for (auto& scan : open_scans_) {
        if (scan.index >= map.first_scan && scan.index <= map.last_scan) {
            scans.push_back(std::move(scan.points_in_sensor));
            T_map_scan.push_back(T_map_world * scan.T_world_sensor);
        } else {
            *kept++ = std::move(scan);
        }
    }
    open_scans_.erase(kept, open_scans_.end());
    // A beam's last two cells are not free: range noise and the wall's own thickness.
    observed_.emplace_back(scans, T_map_scan, cell_, 2.0 * cell_);
}

bool FreeSpaceGate::Judges(int query, int ref) const {
    return active_ && query >= 0 && ref >= 0 && std::size_t(std::max(query, ref)) < observed_.size();
}

RefinementConfig FreeSpaceGate::Registration(const RefinementConfig& refinement, int query, int ref) const {
    RefinementConfig gates = refinement;
    if (Judges(query, ref) && !overlap_explicit_) gates.min_overlap = 0.0;
    return gates;
}

void FreeSpaceGate::Judge(RefinementResult& result, const RefinementConfig& refinement, int query, int ref) const {
    if (!Judges(query, ref) || !result.accepted || result.overlap >= refinement.min_overlap) return;
    // A pair that shares little of the smaller map's extent (a crossing, a corridor run along) is
    // accepted when what both maps observed agrees; a pair above the overlap gate is judged as before.
    const auto ref_in_query = Agreement(observed_[std::size_t(query)], observed_[std::size_t(ref)], result.T_query_ref);
    const auto query_in_ref = Agreement(observed_[std::size_t(ref)], observed_[std::size_t(query)], result.T_query_ref.inverse());
    char text[240];
    if (ref_in_query.observed() < min_observed_ || query_in_ref.observed() < min_observed_) {
        std::snprintf(text, sizeof(text),
                      "overlap %.3g below %.3g and free space: the maps observed %d and %d of each other's wall cells, below %d",
                      result.overlap, refinement.min_overlap, ref_in_query.observed(), query_in_ref.observed(), min_observed_);
    } else if (ref_in_query.ratio() < min_agreement_ || query_in_ref.ratio() < min_agreement_) {
        std::snprintf(text, sizeof(text),
                      "overlap %.3g below %.3g and free space: %.2f and %.2f of the walls agree with the other map's view, below %.2f",
                      result.overlap, refinement.min_overlap, ref_in_query.ratio(), query_in_ref.ratio(), min_agreement_);
    } else {
        return;
    }
    result.accepted = false;
    result.reason = text;
}

}  // namespace revisit
