#pragma once
/// Anderson acceleration of a fixed-point iteration in R^6 (issue 19): ICP's Gauss-Newton steps from a
/// poor initial guess crawl (point-to-point correspondences move the pose by a fraction of the error per
/// iteration, consecutive steps pointing the same way); extrapolating from the last few steps reaches
/// the same fixed point in fewer iterations. Walker & Ni, "Anderson acceleration for fixed-point
/// iterations" (SIAM J. Numer. Anal. 2011); for ICP: Pavlov et al. 2018, Zhang et al. 2021.
#include <Eigen/Core>
#include <vector>

namespace revisit {

class AndersonAccelerator {
  public:
    using Vector6 = Eigen::Matrix<double, 6, 1>;

    /// `depth`: how many previous steps the extrapolation combines (0: none, Next returns g).
    explicit AndersonAccelerator(int depth) : depth_(depth) {}

    /// The next iterate after `y`, whose plain image is `g` = G(y): g - dG gamma, with gamma the least-
    /// squares combination of the last steps' residual changes that best cancels the residual g - y.
    /// `extrapolated` tells whether it differs from g (not while the history is too short).
    Vector6 Next(const Vector6& y, const Vector6& g, bool& extrapolated);
    /// Forgets the history (after an extrapolation was rejected).
    void Reset();

  private:
    int depth_;
    std::vector<Vector6> residuals_;  ///< g - y of the last depth + 1 iterates, oldest first
    std::vector<Vector6> images_;     ///< their g
};

}  // namespace revisit
