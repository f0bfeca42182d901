#include "odometry/adaptive_threshold.hpp"

#include <cmath>

#include "core/se3.hpp"

namespace revisit {

double ModelError(const Eigen::Isometry3d& deviation, double max_range) {
    const double theta = RotationAngle(deviation);
    return deviation.translation().norm() + 2.0 * max_range * std::sin(theta / 2.0);
}

void AdaptiveThreshold::Update(const Eigen::Isometry3d& model_deviation) {
    const double error = ModelError(model_deviation, max_range_);
    if (!std::isfinite(error) || error <= min_motion_th_) return;
    sum_squared_errors_ += error * error;
    ++num_samples_;
}

double AdaptiveThreshold::Sigma() const {
    if (num_samples_ == 0) return initial_threshold_;
    return std::sqrt(sum_squared_errors_ / static_cast<double>(num_samples_));
}

}  // namespace revisit
