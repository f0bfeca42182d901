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
/// is estimated from the data as the registered-minus-prior rotation per metre of prior travel, in
/// blocks of travel, and the prior is corrected by it when the blocks agree (a steady bias). Fixed
/// point: the corrected prior's residual bias shrinks to zero even though each registration keeps a
/// share of it.
#include <Eigen/Geometry>
#include <deque>
#include <utility>

namespace revisit {

struct PriorBiasConfig {
    bool enabled = true;         ///< (the odometry's switch is OdometryConfig::prior_bias_correction, on by default)
    double window = 50.0;        ///< [m] of prior travel per block: each block measures one rate
    int blocks = 8;              ///< the estimate is the mean rate of the last this many blocks
    int min_blocks = 3;          ///< nothing is removed before this many blocks
    /// A platform's bias is steady: |mean rate| / RMS of the blocks' rates at least this, else nothing
    /// is removed. Measured per 50 m: intel +0.054..+0.062 rad/m (0.99), fr079 +0.012..+0.022 (0.95);
    /// mit-killian wanders between -0.019 and +0.021 with changes of sign, and removing its "bias" bent
    /// its corridors.
    double min_steadiness = 0.7;
};

class PriorRotationBias {
  public:
    explicit PriorRotationBias(const PriorBiasConfig& config = {}) : config_(config) {}

    /// The prior increment T_prev_next with the estimated bias removed (the rotation it gained over its travel).
    Eigen::Isometry3d Correct(const Eigen::Isometry3d& prior_delta) const;
    /// One registered frame: the raw prior increment and the increment the registration found.
    void Update(const Eigen::Isometry3d& prior_delta, const Eigen::Isometry3d& registered_delta);
    /// [rad/m] The current estimate (rotation vector per metre, in the sensor frame); zero until it is
    /// applied (enough blocks, steady).
    Eigen::Vector3d RatePerMetre() const { return rate_; }

  private:
    void CloseBlock();

    PriorBiasConfig config_;
    Eigen::Vector3d block_rotation_ = Eigen::Vector3d::Zero();  ///< [rad] registered-minus-prior rotations of the open block
    double block_travel_ = 0.0;                                 ///< [m] its prior travel
    std::deque<std::pair<Eigen::Vector3d, double>> blocks_;     ///< closed blocks: rotation [rad], travel [m]
    Eigen::Vector3d rate_ = Eigen::Vector3d::Zero();            ///< [rad/m] what Correct removes
};

}  // namespace revisit
