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

double ToleranceExcess(double chi2, double tolerance) {
    if (!(tolerance > 0.0)) return chi2;
    if (chi2 <= tolerance) return 0.0;
    if (chi2 <= 2.0 * tolerance) return (chi2 - tolerance) * (chi2 - tolerance) / (2.0 * tolerance);
    return chi2 - 1.5 * tolerance;
}

void ToleranceLoss::Evaluate(double s, double rho[3]) const {
    // h and its derivatives, then the chain rule through the inner kernel.
    double h = s, dh = 1.0, ddh = 0.0;
    if (tolerance_ > 0.0) {
        h = ToleranceExcess(s, tolerance_);
        dh = s <= tolerance_ ? 0.0 : s <= 2.0 * tolerance_ ? (s - tolerance_) / tolerance_ : 1.0;
        ddh = s > tolerance_ && s <= 2.0 * tolerance_ ? 1.0 / tolerance_ : 0.0;
    }
    double inner[3] = {h, 1.0, 0.0};
    if (inner_) inner_->Evaluate(h, inner);
    rho[0] = inner[0];
    rho[1] = inner[1] * dh;
    rho[2] = inner[2] * dh * dh + inner[1] * ddh;
    // Ceres' corrector asks rho' > 0 wherever rho'' > 0; inside the band both are 0 (the edge is off).
    if (!(rho[1] > 0.0)) rho[1] = rho[2] = 0.0;
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

std::unique_ptr<ceres::LossFunction> MakeLoopLoss(RobustLossKind kind, double scale, double tolerance) {
    if (!(tolerance > 0.0)) return MakeRobustLoss(kind, scale);
    return std::make_unique<ToleranceLoss>(tolerance, MakeRobustLoss(kind, scale));
}

double LoopWeight(RobustLossKind kind, double scale, double tolerance, double chi2) {
    return RobustWeight(kind, scale, ToleranceExcess(chi2, tolerance));
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
