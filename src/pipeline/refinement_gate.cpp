#include "pipeline/refinement_gate.hpp"

#include <cstdio>

namespace revisit {
namespace {

/// The smear gate's factor is the default RMS gate's ratio to what consecutive 3D street maps show under
/// good odometry (METHOD.md section 7). A gate chosen otherwise (2D lasers: two map voxels; a preset;
/// --set) has its own calibration and stays fixed.
double SmearGateFactor(const PipelineConfig& config) {
    const bool default_gate = !config.odometry.planar && config.refinement.max_rms == RefinementConfig{}.max_rms &&
                              config.explicit_keys.count("refinement.max_rms") == 0;
    return default_gate ? config.refinement.smear_gate_factor : 0.0;
}

}  // namespace

RefinementGate::RefinementGate(const PipelineConfig& config)
    : refinement_(config.refinement), factor_(SmearGateFactor(config)), smear_gate_(factor_) {}

void RefinementGate::AddConsecutive(const std::vector<Eigen::Vector3d>& ref_points_in_ref,
                                    const std::vector<Eigen::Vector3d>& query_points_in_query,
                                    const Eigen::Isometry3d& T_query_ref_odometry, std::size_t first_scan,
                                    const RefinementQuery* prepared) {
    if (!active()) return;
    const bool reuse = prepared && prepared->SamePlanesAs(Eigen::Vector3d::UnitZ());
    smear_gate_.Add(reuse ? RegisterConsecutive(ref_points_in_ref, *prepared, T_query_ref_odometry, refinement_)
                          : RegisterConsecutive(ref_points_in_ref, query_points_in_query, T_query_ref_odometry, refinement_),
                    refinement_.min_correspondences);
    if (!raised_at_ && smear_gate_.MaxRms(refinement_.max_rms) > refinement_.max_rms) raised_at_ = first_scan;
}

RefinementConfig RefinementGate::Refinement() const {
    RefinementConfig gated = refinement_;
    gated.max_rms = smear_gate_.MaxRms(refinement_.max_rms);
    return gated;
}

std::optional<SettingUpdate> RefinementGate::Update() const {
    const double configured = refinement_.max_rms;
    const double gate = smear_gate_.MaxRms(configured);
    if (!(gate > configured)) return std::nullopt;
    char reason[160];
    std::snprintf(reason, sizeof(reason), "consecutive maps register at a median RMS of %.3g m (x %.3g): the odometry smears the maps",
                  smear_gate_.MedianRms(), factor_);
    // The scan of the first map verified above the configured gate; the value is the final one.
    return SettingUpdate{raised_at_.value_or(0), "refinement.max_rms", configured, gate, reason};
}

}  // namespace revisit
