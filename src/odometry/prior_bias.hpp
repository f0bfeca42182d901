#pragma once
/// The rotation bias of a motion prior (wheel odometry), measured against the scan registration and
/// removed from the prior before it seeds ICP.
///
/// Why: ICP started from a prior whose heading is off keeps part of the error. Point-to-point residuals
/// against map points a few centimetres apart along a wall cannot resolve rotations that move the scan
/// by less than that spacing, so each scan keeps a share of the prior's turn error and the share adds up
/// along the path. Measured on radish intel (a differential drive whose heading drifts 0.05 rad per metre
/// against the scan matching): 9% of that bias survived registration, a heading drift of 4.3e-3 rad/m in
/// the odometry. The bias is a property of the platform (unequal wheel radii: per metre of travel), so it
/// is estimated from the data as the registered-minus-prior rotation per metre of prior travel, over a
/// travel window, and the prior is corrected by it. Fixed point: the corrected prior's residual bias
/// shrinks to zero even though each registration keeps a share of it.
#include <Eigen/Geometry>

namespace revisit {

struct PriorBiasConfig {
    bool enabled = true;         ///< (the odometry's switch is OdometryConfig::prior_bias_correction, off by default)
    double window = 50.0;        ///< [m] of prior travel over which the bias is averaged (exponential forgetting)
    double min_travel = 2.0;     ///< [m] of registered travel before the estimate is applied
};

class PriorRotationBias {
  public:
    explicit PriorRotationBias(const PriorBiasConfig& config = {}) : config_(config) {}

    /// The prior increment T_prev_next with the estimated bias removed (the rotation it gained over its travel).
    Eigen::Isometry3d Correct(const Eigen::Isometry3d& prior_delta) const;
    /// One registered frame: the raw prior increment and the increment the registration found.
    void Update(const Eigen::Isometry3d& prior_delta, const Eigen::Isometry3d& registered_delta);
    /// [rad/m] The current estimate (rotation vector per metre, in the sensor frame); zero until applied.
    Eigen::Vector3d RatePerMetre() const;

  private:
    PriorBiasConfig config_;
    Eigen::Vector3d weighted_rotation_ = Eigen::Vector3d::Zero();  ///< [rad] sum of registered-minus-prior rotations
    double weighted_travel_ = 0.0;                                 ///< [m] the matching sum of prior travel
    double total_travel_ = 0.0;                                    ///< [m] all registered prior travel
};

}  // namespace revisit
