#pragma once
/// Robust losses of loop-closure edges, on chi^2 = e' Omega e, and their final weights.
#include <ceres/loss_function.h>

#include <memory>

namespace revisit {

enum class RobustLossKind {
    kNone,                      ///< plain least squares: one wrong closure bends the map
    kCauchy,                    ///< rho(s) = c log(1 + s / c), weight 1 / (1 + s / c)
    kDynamicCovarianceScaling,  ///< Agarwal et al. ICRA 2013, weight min(1, 2 Phi / (Phi + s))^2
};

/// Dynamic covariance scaling as an M-estimator: rho(s) = s for s <= Phi, else
/// 3 Phi - 4 Phi^2 / (Phi + s), so that rho'(s) is exactly DCS' squared scale factor
/// (Agarwal et al. 2013); continuous with continuous first derivative at Phi.
class DynamicCovarianceScalingLoss : public ceres::LossFunction {
  public:
    explicit DynamicCovarianceScalingLoss(double phi) : phi_(phi) {}
    void Evaluate(double s, double rho[3]) const override;

  private:
    double phi_;
};

/// The loss for `kind` with scale `scale` (Phi or c, on chi^2), or nullptr for kNone.
std::unique_ptr<ceres::LossFunction> MakeRobustLoss(RobustLossKind kind, double scale);

/// The weight rho'(chi2) the loss gives an edge with squared whitened error `chi2`, in [0, 1].
double RobustWeight(RobustLossKind kind, double scale, double chi2);

}  // namespace revisit
