#include "settings/laser_aperture.hpp"

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

/// Range of `beams` at fractional beam index u (linear between two valid neighbours), or 0.
float RangeAt(const std::vector<float>& ranges, double u) {
    const auto i = static_cast<std::size_t>(std::floor(u));
    if (u < 0.0 || i + 1 >= ranges.size()) return 0.f;
    const float a = ranges[i], b = ranges[i + 1];
    if (a <= 0.f || b <= 0.f) return 0.f;
    const double w = u - static_cast<double>(i);
    return static_cast<float>((1.0 - w) * a + w * b);
}

/// Mean clipped range difference of `later`'s beams, placed with scale k and moved into `earlier`'s
/// frame, against `earlier`; negative when fewer than a quarter of the beams land on valid ones.
double ScaleCost(const PlanarBeams& earlier, const PlanarBeams& later, const Eigen::Isometry3d& T_earlier_later, double k) {
    const std::size_t n = later.ranges.size();
    const double step = later.aperture / static_cast<double>(n - 1);
    double sum = 0.0;
    std::size_t count = 0;
    for (std::size_t j = 0; j < n; ++j) {
        const float r = later.ranges[j];
        if (r <= 0.f) continue;
        const double angle = k * (-0.5 * later.aperture + step * static_cast<double>(j));
        const Eigen::Vector3d q = T_earlier_later * Eigen::Vector3d(r * std::cos(angle), r * std::sin(angle), 0.0);
        const double u = (std::atan2(q.y(), q.x()) / k + 0.5 * earlier.aperture) / step;
        const float expected = RangeAt(earlier.ranges, u);
        if (expected <= 0.f) continue;
        sum += std::min(std::abs(static_cast<float>(q.head<2>().norm()) - expected), kClip);
        ++count;
    }
    return count >= n / 4 ? sum / static_cast<double>(count) : -1.0;
}

}  // namespace

std::optional<double> ApertureScale(const PlanarBeams& earlier, const PlanarBeams& later, const Eigen::Isometry3d& T_earlier_later,
                                    const ApertureCheckConfig& config) {
    if (earlier.ranges.size() != later.ranges.size() || later.ranges.size() < 8) return std::nullopt;
    std::vector<double> scales, costs;
    for (double k = config.min_scale; k <= config.max_scale; k *= 1.0 + config.scale_step) {
        scales.push_back(k);
        costs.push_back(ScaleCost(earlier, later, T_earlier_later, k));
    }
    std::size_t best = costs.size();
    for (std::size_t m = 0; m < costs.size(); ++m) {
        if (costs[m] >= 0.0 && (best == costs.size() || costs[m] < costs[best])) best = m;
    }
    if (best == costs.size() || best == 0 || best + 1 == costs.size()) return std::nullopt;  // none, or at the edge
    // Sub-step: the vertex of the parabola through the best cost and its neighbours (in log k).
    const double left = costs[best - 1], mid = costs[best], right = costs[best + 1];
    double offset = 0.0;
    if (left >= 0.0 && right >= 0.0 && left - 2.0 * mid + right > 1e-12) {
        offset = std::clamp(0.5 * (left - right) / (left - 2.0 * mid + right), -0.5, 0.5);
    }
    return scales[best] * std::pow(1.0 + config.scale_step, offset);
}

bool ApertureChecker::Add(const Scan& scan) {
    if (Done()) return false;
    if (!scan.planar_beams || !scan.T_odom_sensor || scan.planar_beams->ranges.size() < 8) return true;
    const auto& beams = *scan.planar_beams;
    if (beams_ != 0 && (static_cast<std::size_t>(beams_) != beams.ranges.size() || beams.aperture != used_)) return true;
    beams_ = static_cast<int>(beams.ranges.size());
    stated_ = beams.stated_aperture;
    used_ = beams.aperture;
    // Pair with the most recent earlier scan whose turn is measurable.
    for (auto it = past_.rbegin(); it != past_.rend(); ++it) {
        const Eigen::Isometry3d delta = it->T_odom_sensor.inverse() * *scan.T_odom_sensor;
        const double turn = Yaw(delta);
        if (std::abs(turn) < config_.min_turn_deg * kDeg || std::abs(turn) > config_.max_turn_deg * kDeg) continue;
        if (delta.translation().head<2>().norm() > config_.max_translation) continue;
        const Eigen::Isometry3d T_earlier_later = beams.T_vehicle_sensor.inverse() * delta * beams.T_vehicle_sensor;
        if (const auto scale = ApertureScale(it->beams, beams, T_earlier_later, config_)) ratios_.push_back(*scale);
        break;
    }
    past_.push_back({beams, *scan.T_odom_sensor});
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
    // Wrong apertures come from unit or half-angle slips (90 stated for 180): a ratio within 5% of a
    // multiple of 1/2 is taken as that multiple; the result is rounded to whole degrees.
    const double half_multiple = std::round(2.0 * e.ratio) / 2.0;
    const double ratio = half_multiple > 0.0 && std::abs(e.ratio - half_multiple) <= 0.05 * e.ratio ? half_multiple : e.ratio;
    e.measured_deg = std::round(e.used_deg * ratio);
    e.contradicts = std::abs(e.ratio - 1.0) > config_.tolerance && e.ratio_spread < 0.25 * e.ratio;
    return e;
}

std::string ApertureEstimate::Describe() const {
    std::ostringstream out;
    out << std::fixed << std::setprecision(1) << beams << " beams, stated aperture " << stated_deg << " deg";
    if (std::abs(used_deg - stated_deg) > 1e-6) out << " (used " << used_deg << " deg)";
    out << "; " << pairs << " turns of 8-45 deg measure " << measured_deg << " deg (ratio " << std::setprecision(2) << ratio
        << " +- " << ratio_spread << ")";
    return out.str();
}

}  // namespace revisit
