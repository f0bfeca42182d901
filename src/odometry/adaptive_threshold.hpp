#pragma once
/// The adaptive correspondence threshold of KISS-ICP (METHOD.md section 1).
#include <Eigen/Geometry>
#include <cstddef>

namespace revisit {

/// Model error of a motion deviation: |t| + 2 max_range sin(theta / 2) [m], the largest
/// displacement the deviation causes on a point within max_range (METHOD.md section 1).
double ModelError(const Eigen::Isometry3d& deviation, double max_range);

class AdaptiveThreshold {
  public:
    AdaptiveThreshold(double initial_threshold, double min_motion_th, double max_range)
        : initial_threshold_(initial_threshold), min_motion_th_(min_motion_th), max_range_(max_range) {}

    /// Records the deviation between the predicted and the registered pose of a frame; only
    /// deviations whose model error exceeds min_motion_th count (standing still says nothing).
    void Update(const Eigen::Isometry3d& model_deviation);
    /// sigma = sqrt(mean of the counted model errors^2) [m], or the initial threshold before any.
    double Sigma() const;
    std::size_t NumSamples() const { return num_samples_; }
    /// The lever arm of later model errors (the crop radius changed mid-run; earlier errors stay).
    void SetMaxRange(double max_range) { max_range_ = max_range; }

  private:
    double initial_threshold_;
    double min_motion_th_;
    double max_range_;
    double sum_squared_errors_ = 0.0;
    std::size_t num_samples_ = 0;
};

}  // namespace revisit
