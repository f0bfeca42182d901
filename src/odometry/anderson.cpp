#include "odometry/anderson.hpp"

#include <Eigen/QR>

namespace revisit {

AndersonAccelerator::Vector6 AndersonAccelerator::Next(const Vector6& y, const Vector6& g, bool& extrapolated) {
    extrapolated = false;
    if (depth_ <= 0) return g;
    residuals_.push_back(g - y);
    images_.push_back(g);
    if (residuals_.size() > static_cast<std::size_t>(depth_) + 1) {
        residuals_.erase(residuals_.begin());
        images_.erase(images_.begin());
    }
    const int m = static_cast<int>(residuals_.size()) - 1;
    if (m < 1) return g;
    Eigen::Matrix<double, 6, Eigen::Dynamic> dF(6, m), dG(6, m);
    for (int j = 0; j < m; ++j) {
        dF.col(j) = residuals_[j + 1] - residuals_[j];
        dG.col(j) = images_[j + 1] - images_[j];
    }
    // Rank-revealing: collinear steps (the usual crawl) make dF rank-deficient.
    const Eigen::VectorXd gamma = dF.colPivHouseholderQr().solve(residuals_.back());
    if (!gamma.allFinite()) return g;
    extrapolated = true;
    return g - dG * gamma;
}

void AndersonAccelerator::Reset() {
    residuals_.clear();
    images_.clear();
}

}  // namespace revisit
