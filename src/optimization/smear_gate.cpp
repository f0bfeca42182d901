#include "optimization/smear_gate.hpp"

#include <algorithm>

#include "core/quantile.hpp"

namespace revisit {

void SmearGate::Add(const RefinementResult& consecutive, int min_correspondences) {
    if (!active() || consecutive.num_correspondences < std::max(6, min_correspondences)) return;
    rms_.push_back(consecutive.rms);
}

double SmearGate::MedianRms() const { return Quantile(rms_, 0.5); }

double SmearGate::MaxRms(double configured) const {
    if (!active() || rms_.empty()) return configured;
    return std::max(configured, factor_ * MedianRms());
}

RefinementResult RegisterConsecutive(const std::vector<Eigen::Vector3d>& ref_points_in_ref,
                                     const std::vector<Eigen::Vector3d>& query_points_in_query,
                                     const Eigen::Isometry3d& T_query_ref_odometry, const RefinementConfig& config) {
    RefinementConfig consecutive = config;
    consecutive.vertical_search = 0.0;
    return RefineAlignment(ref_points_in_ref, query_points_in_query, T_query_ref_odometry, consecutive);
}

RefinementResult RegisterConsecutive(const std::vector<Eigen::Vector3d>& ref_points_in_ref, const RefinementQuery& query,
                                     const Eigen::Isometry3d& T_query_ref_odometry, const RefinementConfig& config) {
    RefinementConfig consecutive = config;
    consecutive.vertical_search = 0.0;
    return RefineAlignment(ref_points_in_ref, query, T_query_ref_odometry, consecutive);
}

}  // namespace revisit
