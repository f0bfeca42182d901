#include "odometry/prior_bias.hpp"

#include <algorithm>
#include <cmath>

namespace revisit {
namespace {

Eigen::Vector3d Log(const Eigen::Matrix3d& R) {
    const Eigen::AngleAxisd aa(R);
    return aa.angle() * aa.axis();
}

}  // namespace

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
    block_rotation_ += difference;
    block_travel_ += travel;
    if (block_travel_ >= config_.window) CloseBlock();
}

void PriorRotationBias::CloseBlock() {
    blocks_.emplace_back(block_rotation_, block_travel_);
    block_rotation_.setZero();
    block_travel_ = 0.0;
    while (blocks_.size() > std::size_t(std::max(1, config_.blocks))) blocks_.pop_front();
    rate_.setZero();
    if (blocks_.size() < std::size_t(std::max(1, config_.min_blocks))) return;
    Eigen::Vector3d rotation = Eigen::Vector3d::Zero();
    double travel = 0.0, sum_squared_rates = 0.0;
    for (const auto& [block_rotation, block_travel] : blocks_) {
        rotation += block_rotation;
        travel += block_travel;
        sum_squared_rates += (block_rotation / block_travel).squaredNorm();
    }
    const Eigen::Vector3d mean = rotation / travel;
    const double rms = std::sqrt(sum_squared_rates / double(blocks_.size()));
    // A wandering disagreement (no platform bias) averages out over the blocks; a bias does not.
    if (rms > 0.0 && mean.norm() >= config_.min_steadiness * rms) rate_ = mean;
}

}  // namespace revisit
