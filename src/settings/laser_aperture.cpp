#include "settings/laser_aperture.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <numeric>
#include <sstream>

#include "odometry/correlative_matcher.hpp"

namespace revisit {
namespace {

constexpr double kDeg = M_PI / 180.0;
/// Around a wheel-odometry motion, the match searches only the prior's own error (a few cm over the
/// pair's travel; its turns are right to 5-10%): a wrong aperture turns the scan by turn / k in the
/// placed angles and can then not be matched, while within a search over every rotation a scan
/// squeezed into half its angles still matches its squeezed neighbour.
constexpr double kPriorWindow = 0.3;          ///< [m]
constexpr double kPriorTurnShare = 0.1;       ///< of the turn
constexpr double kPriorTurnFloor = 1.0;       ///< [deg]
/// Without a prior, consecutive scans are matched over the odometry's windows (a laser logged alone).
constexpr double kFreeWindow = 1.5;         ///< [m]
constexpr double kFreeTurnWindow = 45.0;    ///< [deg]

double Yaw(const Eigen::Isometry3d& T) { return std::atan2(T.linear()(1, 0), T.linear()(0, 0)); }

std::vector<Eigen::Vector3d> Place(const PlanarBeams& beams, double aperture) {
    std::vector<Eigen::Vector3d> points;
    const std::size_t n = beams.ranges.size();
    const double step = aperture / static_cast<double>(n - 1);
    for (std::size_t j = 0; j < n; ++j) {
        const float r = beams.ranges[j];
        if (!(r > 0.f) || !std::isfinite(r)) continue;
        const double angle = -0.5 * aperture + step * static_cast<double>(j);
        points.emplace_back(r * std::cos(angle), r * std::sin(angle), 0.0);
    }
    return points;
}

/// A cell of a fiftieth of the scan's median range (2 cm at intel's 1.4 m, 5 cm at 2.6 m).
double CellFor(const std::vector<Eigen::Vector3d>& points) {
    if (points.empty()) return 0.05;
    std::vector<double> ranges;
    for (const auto& p : points) ranges.push_back(p.head<2>().norm());
    const auto mid = ranges.begin() + static_cast<std::ptrdiff_t>(ranges.size() / 2);
    std::nth_element(ranges.begin(), mid, ranges.end());
    return std::clamp(*mid / 50.0, 0.02, 0.5);
}

struct PairedTest {
    double mean = 0.0;  ///< mean of a - b
    double t = 0.0;     ///< mean / standard error (large when every pair agrees)
};

PairedTest Paired(const std::vector<std::vector<double>>& scores, std::size_t a, std::size_t b) {
    std::vector<double> d;
    for (const auto& s : scores) d.push_back(s[a] - s[b]);
    PairedTest test;
    if (d.size() < 2) return test;
    test.mean = std::accumulate(d.begin(), d.end(), 0.0) / static_cast<double>(d.size());
    double var = 0.0;
    for (double x : d) var += (x - test.mean) * (x - test.mean);
    var /= static_cast<double>(d.size() - 1);
    const double se = std::sqrt(var / static_cast<double>(d.size()));
    test.t = se > 0.0 ? test.mean / se : (test.mean > 0.0 ? 1e9 : (test.mean < 0.0 ? -1e9 : 0.0));
    return test;
}

}  // namespace

double PairScore(const PlanarBeams& earlier, const PlanarBeams& later, double aperture, const Eigen::Isometry3d& T_earlier_later,
                 double linear_window, double angular_window) {
    const auto reference = Place(earlier, aperture), points = Place(later, aperture);
    if (reference.size() < 8 || points.size() < 8) return 0.0;
    CorrelativeMatchConfig config;
    config.resolution = CellFor(reference);
    config.linear_window = linear_window;
    config.angular_window = angular_window;
    return MatchCorrelative2D(reference, points, T_earlier_later, config).score;
}

bool ApertureChecker::Add(const Scan& scan) {
    if (Done()) return false;
    if (!scan.planar_beams || scan.planar_beams->ranges.size() < 8) return true;
    const auto& beams = *scan.planar_beams;
    if (beams_ != 0 && (static_cast<std::size_t>(beams_) != beams.ranges.size() || beams.aperture != used_)) return true;
    if (beams_ == 0) {
        beams_ = static_cast<int>(beams.ranges.size());
        stated_ = beams.stated_aperture;
        used_ = beams.aperture;
        candidates_deg_ = {used_ / kDeg};
        for (double a : config_.standard_deg)
            if (std::abs(a - used_ / kDeg) > 0.01) candidates_deg_.push_back(a);
    }
    // With wheel odometry: the most recent earlier scan it moved measurably from (its motion guides the
    // match). Without: the previous scan, matched over the odometry's windows.
    const Past* partner = nullptr;
    Eigen::Isometry3d T_earlier_later = Eigen::Isometry3d::Identity();
    double linear = kFreeWindow, angular = kFreeTurnWindow * kDeg;
    if (scan.T_odom_sensor) {
        for (auto it = past_.rbegin(); it != past_.rend(); ++it) {
            if (!it->T_odom_sensor) continue;
            const Eigen::Isometry3d delta = it->T_odom_sensor->inverse() * *scan.T_odom_sensor;
            const double turn = std::abs(Yaw(delta)), travel = delta.translation().head<2>().norm();
            if (travel > config_.max_translation || turn > config_.max_turn_deg * kDeg) break;
            // A turn is what a wrong aperture cannot follow (walls along a corridor look alike under any).
            if (turn < config_.min_turn_deg * kDeg) continue;
            partner = &*it;
            T_earlier_later = beams.T_vehicle_sensor.inverse() * delta * beams.T_vehicle_sensor;
            linear = kPriorWindow;
            angular = kPriorTurnShare * turn + kPriorTurnFloor * kDeg;
            break;
        }
    } else if (!past_.empty()) {
        partner = &past_.back();
    }
    if (partner != nullptr) {
        std::vector<double> scores;
        for (double a : candidates_deg_) scores.push_back(PairScore(partner->beams, beams, a * kDeg, T_earlier_later, linear, angular));
        pair_scores_.push_back(std::move(scores));
        // A scan is paired once: the next pair starts from a scan after this one.
        past_.clear();
    }
    past_.push_back({beams, scan.T_odom_sensor, scan.index});
    if (past_.size() > config_.window) past_.erase(past_.begin());
    return !Done();
}

std::optional<ApertureEstimate> ApertureChecker::Estimate() const {
    if (pair_scores_.size() < config_.min_pairs || beams_ == 0) return std::nullopt;
    ApertureEstimate e;
    e.beams = beams_;
    e.stated_deg = stated_ / kDeg;
    e.used_deg = used_ / kDeg;
    e.pairs = pair_scores_.size();
    const std::size_t k = candidates_deg_.size();
    std::vector<double> mean(k, 0.0);
    for (const auto& s : pair_scores_)
        for (std::size_t c = 0; c < k; ++c) mean[c] += s[c] / static_cast<double>(pair_scores_.size());
    // Candidates better than the used aperture beyond doubt; of those, the best and every one it does
    // not beat beyond doubt are the data's answer (180, 180.5 and 190 deg place a 180-beam scan within
    // a few percent of each other, and turns do not tell them apart): the smallest change among them.
    std::vector<std::size_t> better;
    for (std::size_t c = 1; c < k; ++c)
        if (Paired(pair_scores_, c, 0).t >= config_.min_t) better.push_back(c);
    const std::size_t best = static_cast<std::size_t>(std::max_element(mean.begin(), mean.end()) - mean.begin());
    std::size_t chosen = 0;
    if (!better.empty()) {
        std::size_t top = better.front();
        for (std::size_t c : better)
            if (mean[c] > mean[top]) top = c;
        chosen = top;
        const auto change = [&](std::size_t c) { return std::abs(std::log(candidates_deg_[c] / candidates_deg_[0])); };
        for (std::size_t c : better)
            if (c != top && Paired(pair_scores_, top, c).t < config_.min_t && change(c) < change(chosen)) chosen = c;
    }
    const std::size_t shown = chosen != 0 ? chosen : best;
    std::size_t runner_up = shown == 0 && k > 1 ? 1 : 0;
    for (std::size_t c = 0; c < k; ++c)
        if (c != shown && mean[c] > mean[runner_up]) runner_up = c;
    e.measured_deg = candidates_deg_[shown];
    e.measured_score = mean[shown];
    e.used_score = mean[0];
    e.runner_up_deg = candidates_deg_[runner_up];
    e.t_used = shown == 0 ? 0.0 : Paired(pair_scores_, shown, 0).t;
    e.t_runner_up = Paired(pair_scores_, shown, runner_up).t;
    e.contradicts = chosen != 0;
    e.doubtful = chosen == 0 && best != 0;
    return e;
}

std::string ApertureEstimate::Describe() const {
    std::ostringstream out;
    out << std::fixed << std::setprecision(1) << beams << " beams, stated aperture " << stated_deg << " deg";
    if (std::abs(used_deg - stated_deg) > 1e-6) out << " (used " << used_deg << " deg)";
    out << "; " << pairs << " scan pairs agree best at " << measured_deg << " deg (match score " << std::setprecision(3)
        << measured_score << " against " << used_score << " at " << std::setprecision(1) << used_deg << " deg, paired t "
        << t_used << "; next best " << runner_up_deg << " deg, t " << t_runner_up << ")";
    return out.str();
}

}  // namespace revisit
