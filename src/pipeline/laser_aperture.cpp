#include "pipeline/laser_aperture.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

namespace revisit {
namespace {

constexpr double kDeg = M_PI / 180.0;
constexpr float kClip = 1.0f;  ///< [m] range differences are clipped here: moving people, glass

double Median(std::vector<double> values) {
    const auto mid = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
    std::nth_element(values.begin(), mid, values.end());
    return *mid;
}

double Yaw(const Eigen::Isometry3d& T) { return std::atan2(T.linear()(1, 0), T.linear()(0, 0)); }

/// Mean clipped |earlier[i + s] - later[i]| over beams valid in both; negative when the overlap is
/// below half the beams.
double ShiftCost(const std::vector<float>& earlier, const std::vector<float>& later, int s) {
    const int n = static_cast<int>(later.size());
    double sum = 0.0;
    int count = 0;
    for (int i = std::max(0, -s); i < std::min(n, n - s); ++i) {
        const float a = earlier[static_cast<std::size_t>(i + s)], b = later[static_cast<std::size_t>(i)];
        if (a <= 0.f || b <= 0.f) continue;
        sum += std::min(std::abs(a - b), kClip);
        ++count;
    }
    return count >= n / 2 ? sum / count : -1.0;
}

}  // namespace

std::optional<double> ProfileShift(const std::vector<float>& earlier, const std::vector<float>& later, int max_shift) {
    if (earlier.size() != later.size() || later.size() < 8) return std::nullopt;
    std::vector<double> cost(static_cast<std::size_t>(2 * max_shift + 1), -1.0);
    int best = 0;
    double best_cost = -1.0;
    for (int s = -max_shift; s <= max_shift; ++s) {
        const double c = ShiftCost(earlier, later, s);
        cost[static_cast<std::size_t>(s + max_shift)] = c;
        if (c >= 0.0 && (best_cost < 0.0 || c < best_cost)) best_cost = c, best = s;
    }
    if (best_cost < 0.0) return std::nullopt;
    // Sub-beam: the vertex of the parabola through the best cost and its two neighbours.
    const auto at = [&](int s) { return std::abs(s) <= max_shift ? cost[static_cast<std::size_t>(s + max_shift)] : -1.0; };
    const double left = at(best - 1), right = at(best + 1);
    double offset = 0.0;
    if (left >= 0.0 && right >= 0.0) {
        const double curvature = left - 2.0 * best_cost + right;
        if (curvature > 1e-12) offset = std::clamp(0.5 * (left - right) / curvature, -0.5, 0.5);
    }
    return best + offset;
}

bool ApertureChecker::Add(const Scan& scan) {
    if (Done()) return false;
    if (!scan.planar_beams || !scan.T_odom_sensor || scan.planar_beams->ranges.size() < 8) return true;
    const auto& beams = *scan.planar_beams;
    if (beams_ != 0 && (static_cast<std::size_t>(beams_) != beams.ranges.size() || beams.aperture != used_)) return true;
    beams_ = static_cast<int>(beams.ranges.size());
    stated_ = beams.stated_aperture;
    used_ = beams.aperture;
    const double step = used_ / static_cast<double>(beams_ - 1);
    // Pair with the most recent earlier scan whose turn is measurable.
    for (auto it = past_.rbegin(); it != past_.rend(); ++it) {
        const Eigen::Isometry3d delta = it->T_odom_sensor.inverse() * *scan.T_odom_sensor;
        const double turn = Yaw(delta);
        if (std::abs(turn) < config_.min_turn_deg * kDeg || std::abs(turn) > config_.max_turn_deg * kDeg) continue;
        if (delta.translation().head<2>().norm() > config_.max_translation) continue;
        // Search shifts up to what a 3x larger or smaller aperture would give.
        const int max_shift = std::min(beams_ / 2, static_cast<int>(std::ceil(3.0 * std::abs(turn) / step)) + 2);
        const auto shift = ProfileShift(it->ranges, beams.ranges, max_shift);
        if (shift && std::abs(*shift) >= 1.0 && (*shift > 0) == (turn > 0)) {
            // A turn of `turn` shifts the profile by turn / true_step beams: true / used = turn / (shift * step).
            ratios_.push_back(turn / (*shift * step));
        }
        break;
    }
    past_.push_back({beams.ranges, *scan.T_odom_sensor});
    if (past_.size() > config_.window) past_.erase(past_.begin());
    return !Done();
}

std::optional<ApertureEstimate> ApertureChecker::Estimate() const {
    if (ratios_.size() < config_.min_pairs || beams_ == 0) return std::nullopt;
    ApertureEstimate e;
    e.beams = beams_;
    e.stated_deg = stated_ / kDeg;
    e.used_deg = used_ / kDeg;
    e.pairs = ratios_.size();
    e.ratio = Median(ratios_);
    std::vector<double> deviations;
    for (double r : ratios_) deviations.push_back(std::abs(r - e.ratio));
    e.ratio_spread = Median(deviations);
    e.measured_deg = e.used_deg * e.ratio;
    // Lasers are built with round fields of view (180, 240, 270, 360 deg): snap when close.
    const double snapped = 5.0 * std::round(e.measured_deg / 5.0);
    if (std::abs(snapped - e.measured_deg) <= 0.025 * e.measured_deg) e.measured_deg = snapped;
    e.contradicts = std::abs(e.ratio - 1.0) > config_.tolerance && e.ratio_spread < 0.25 * e.ratio;
    return e;
}

std::string ApertureEstimate::Describe() const {
    std::ostringstream out;
    out << std::fixed << std::setprecision(1) << beams << " beams, stated aperture " << stated_deg << " deg";
    if (std::abs(used_deg - stated_deg) > 1e-6) out << " (used " << used_deg << " deg)";
    out << "; " << pairs << " turns on the spot measure " << measured_deg << " deg (ratio " << std::setprecision(2) << ratio
        << " +- " << ratio_spread << ")";
    return out.str();
}

}  // namespace revisit
