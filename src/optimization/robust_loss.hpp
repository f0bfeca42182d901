#pragma once
/// Robust losses of loop-closure edges, on chi^2 = e' Omega e, and their final weights.
#include <ceres/loss_function.h>

#include <memory>
#include <utility>

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

/// A closure's tolerance band: the chi^2 that a closure's own registration error explains costs nothing.
/// h(s) = 0 for s <= tau, (s - tau)^2 / (2 tau) up to 2 tau, then s - 1.5 tau (continuous slope, so
/// Levenberg-Marquardt sees no kink). An edge the estimate already satisfies within its uncertainty exerts
/// no pull; one outside it pulls only until it is within. tau <= 0: h(s) = s.
double ToleranceExcess(double chi2, double tolerance);

/// rho(s) = inner(h(s)), h the tolerance band above, inner the robust kernel (nullptr: identity).
class ToleranceLoss : public ceres::LossFunction {
  public:
    ToleranceLoss(double tolerance, std::unique_ptr<ceres::LossFunction> inner)
        : tolerance_(tolerance), inner_(std::move(inner)) {}
    void Evaluate(double s, double rho[3]) const override;

  private:
    double tolerance_;
    std::unique_ptr<ceres::LossFunction> inner_;
};

/// The loss for `kind` with scale `scale` (Phi or c, on chi^2), or nullptr for kNone.
std::unique_ptr<ceres::LossFunction> MakeRobustLoss(RobustLossKind kind, double scale);

/// The robust loss behind a tolerance band of `tolerance` (chi^2); MakeRobustLoss when tolerance <= 0.
std::unique_ptr<ceres::LossFunction> MakeLoopLoss(RobustLossKind kind, double scale, double tolerance);

/// The weight rho'(chi2) the loss gives an edge with squared whitened error `chi2`, in [0, 1].
double RobustWeight(RobustLossKind kind, double scale, double chi2);

/// The robust kernel's weight of an edge behind a tolerance band: RobustWeight at the excess h(chi2),
/// so an edge within its band keeps weight 1 (it agrees; the band only stops it pulling).
double LoopWeight(RobustLossKind kind, double scale, double tolerance, double chi2);

}  // namespace revisit
