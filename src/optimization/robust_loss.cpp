#include "optimization/robust_loss.hpp"

#include <algorithm>
#include <cmath>

namespace revisit {

void DynamicCovarianceScalingLoss::Evaluate(double s, double rho[3]) const {
    if (s <= phi_) {
        rho[0] = s;
        rho[1] = 1.0;
        rho[2] = 0.0;
        return;
    }
    const double denominator = phi_ + s;
    rho[0] = 3.0 * phi_ - 4.0 * phi_ * phi_ / denominator;
    rho[1] = 4.0 * phi_ * phi_ / (denominator * denominator);
    rho[2] = -8.0 * phi_ * phi_ / (denominator * denominator * denominator);
}

std::unique_ptr<ceres::LossFunction> MakeRobustLoss(RobustLossKind kind, double scale) {
    switch (kind) {
        case RobustLossKind::kCauchy:
            // Ceres' CauchyLoss(a) is a^2 log(1 + s / a^2): a^2 plays the role of c.
            return std::make_unique<ceres::CauchyLoss>(std::sqrt(scale));
        case RobustLossKind::kDynamicCovarianceScaling:
            return std::make_unique<DynamicCovarianceScalingLoss>(scale);
        case RobustLossKind::kNone:
            break;
    }
    return nullptr;
}

double RobustWeight(RobustLossKind kind, double scale, double chi2) {
    switch (kind) {
        case RobustLossKind::kCauchy:
            return 1.0 / (1.0 + chi2 / scale);
        case RobustLossKind::kDynamicCovarianceScaling: {
            const double factor = std::min(1.0, 2.0 * scale / (scale + chi2));
            return factor * factor;
        }
        case RobustLossKind::kNone:
            break;
    }
    return 1.0;
}

}  // namespace revisit
