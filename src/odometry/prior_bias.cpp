#include "odometry/prior_bias.hpp"

#include <cmath>

namespace revisit {
namespace {

Eigen::Vector3d Log(const Eigen::Matrix3d& R) {
    const Eigen::AngleAxisd aa(R);
    return aa.angle() * aa.axis();
}

}  // namespace

Eigen::Vector3d PriorRotationBias::RatePerMetre() const {
    if (!config_.enabled || total_travel_ < config_.min_travel || weighted_travel_ <= 0.0) return Eigen::Vector3d::Zero();
    return weighted_rotation_ / weighted_travel_;
}

Eigen::Isometry3d PriorRotationBias::Correct(const Eigen::Isometry3d& prior_delta) const {
    const Eigen::Vector3d rotation = RatePerMetre() * prior_delta.translation().norm();
    if (rotation.isZero()) return prior_delta;
    Eigen::Isometry3d corrected = prior_delta;
    corrected.linear() = prior_delta.linear() * Eigen::AngleAxisd(rotation.norm(), rotation.normalized()).toRotationMatrix();
    return corrected;
}

void PriorRotationBias::Update(const Eigen::Isometry3d& prior_delta, const Eigen::Isometry3d& registered_delta) {
    if (!config_.enabled) return;
    const double travel = prior_delta.translation().norm();
    if (!(travel > 0.0) || !std::isfinite(travel)) return;
    const Eigen::Vector3d difference = Log(prior_delta.linear().transpose() * registered_delta.linear());
    if (!difference.allFinite()) return;
    // Exponential forgetting over the window: a bias that changes (load, tyre wear) is followed.
    const double keep = std::exp(-travel / config_.window);
    weighted_rotation_ = keep * weighted_rotation_ + difference;
    weighted_travel_ = keep * weighted_travel_ + travel;
    total_travel_ += travel;
}

}  // namespace revisit
