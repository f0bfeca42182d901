#include "sim/drive.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "core/se3.hpp"

namespace revisit {
namespace {

constexpr double kTwoPi = 6.283185307179586;
constexpr double kStep = 0.1;  ///< [m] integration step of the path follower

/// The driven geometry before timing: positions, unwrapped heading, arc length and the speed the
/// geometry allows at each vertex.
struct Track {
    std::vector<Eigen::Vector2d> position;
    std::vector<double> heading;       ///< [rad] unwrapped
    std::vector<double> s;             ///< [m]
    std::vector<double> limit;         ///< [m/s]
};

double Cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

/// Walking / indoor: the path as given, heading from a chord of a few metres (so the 1 m
/// resampling does not jitter it), speed from the curvature over +-3 vertices.
Track FollowAsGiven(const std::vector<Eigen::Vector2d>& path, const MotionConfig& config) {
    const std::size_t n = path.size();
    Track track;
    track.position = path;
    track.s.assign(n, 0.0);
    track.heading.assign(n, 0.0);
    track.limit.assign(n, config.cruise_speed);
    for (std::size_t i = 1; i < n; ++i) track.s[i] = track.s[i - 1] + (path[i] - path[i - 1]).norm();
    for (std::size_t i = 0; i < n; ++i) {
        const std::size_t j = std::max<std::size_t>(i, 1);
        const Eigen::Vector2d d = path[std::min(n - 1, j + 2)] - path[j >= 3 ? j - 3 : 0];
        const double yaw = std::atan2(d.y(), d.x());
        // Unwrap against the previous vertex so interpolation never turns the long way round.
        track.heading[i] = i == 0 ? yaw : track.heading[i - 1] + std::remainder(yaw - track.heading[i - 1], kTwoPi);
    }
    for (std::size_t i = 3; i + 3 < n; ++i) {
        const Eigen::Vector2d a = path[i] - path[i - 3];
        const Eigen::Vector2d b = path[i + 3] - path[i];
        const double turn = std::abs(std::atan2(Cross(a, b), a.dot(b)));
        const double curvature = turn / std::max(0.5 * (a.norm() + b.norm()), 1e-6);
        if (curvature > 1e-6) track.limit[i] = std::min(track.limit[i], std::sqrt(config.max_lateral_accel / curvature));
    }
    return track;
}

/// Cars: a pure-pursuit follower of the path whose curvature is bounded by 1/min_turn_radius and
/// changes at a bounded rate per metre, so corners become arcs joined by clothoid-like blends.
/// The speed limit keeps the lateral acceleration, the yaw rate (v*kappa) and its change
/// (v^2 * dkappa/ds while the speed is held through the blend) within the configured limits.
Track FollowWithSteering(const std::vector<Eigen::Vector2d>& path, const MotionConfig& config) {
    const std::size_t n = path.size();
    std::vector<double> ref_s(n, 0.0);
    for (std::size_t i = 1; i < n; ++i) ref_s[i] = ref_s[i - 1] + (path[i] - path[i - 1]).norm();
    const double total = ref_s.back();
    if (total <= 1e-6) return {};
    auto point_at = [&](double s) -> Eigen::Vector2d {
        if (s >= total) {  // beyond the end: straight on, so the follower stays calm at the end
            const Eigen::Vector2d d = (path[n - 1] - path[n - 2]).normalized();
            return path[n - 1] + (s - total) * d;
        }
        const std::size_t i = std::upper_bound(ref_s.begin(), ref_s.end(), s) - ref_s.begin();
        const double f = (s - ref_s[i - 1]) / std::max(ref_s[i] - ref_s[i - 1], 1e-9);
        return path[i - 1] + f * (path[i] - path[i - 1]);
    };
    const double max_curvature = 1.0 / config.min_turn_radius;
    // Curvature change per metre such that v^2 * dkappa/ds stays below max_yaw_accel at the speed
    // that the tightest arc allows (v^2 = a_lat / kappa_max), with a margin.
    const double max_curvature_rate = 0.8 * config.max_yaw_accel * max_curvature / config.max_lateral_accel;
    const double smoothing = 1.5;  // [m] first-order lag of the steering: no chatter from the polyline's kinks

    Track track;
    Eigen::Vector2d p = path.front();
    const Eigen::Vector2d start_direction = point_at(3.0) - p;
    double heading = std::atan2(start_direction.y(), start_direction.x());
    double curvature = 0.0, s = 0.0;
    std::vector<double> kappa;
    std::size_t segment = 0;
    const std::size_t max_steps = static_cast<std::size_t>(3.0 * total / kStep) + 100;
    for (std::size_t step = 0; step < max_steps; ++step) {
        // Projection onto the path, searched a little ahead of the previous one (progress is monotonic).
        double best = std::numeric_limits<double>::infinity(), s_here = ref_s[segment];
        std::size_t best_segment = segment;
        for (std::size_t m = segment; m + 1 < n && m < segment + 40; ++m) {
            const Eigen::Vector2d d = path[m + 1] - path[m];
            const double f = std::clamp((p - path[m]).dot(d) / std::max(d.squaredNorm(), 1e-12), 0.0, 1.0);
            const double distance = (path[m] + f * d - p).squaredNorm();
            if (distance < best) best = distance, best_segment = m, s_here = ref_s[m] + f * d.norm();
        }
        segment = best_segment;
        track.position.push_back(p);
        track.heading.push_back(heading);
        track.s.push_back(s);
        kappa.push_back(curvature);
        if (s_here >= total - 1e-3) break;
        const Eigen::Vector2d to_target = point_at(s_here + config.lookahead) - p;
        const Eigen::Vector2d forward(std::cos(heading), std::sin(heading));
        const double alpha = std::atan2(Cross(forward, to_target), forward.dot(to_target));
        const double wanted = std::clamp(2.0 * std::sin(alpha) / std::max(to_target.norm(), 1e-3), -max_curvature, max_curvature);
        curvature += std::clamp((wanted - curvature) * std::min(1.0, kStep / smoothing), -max_curvature_rate * kStep,
                                max_curvature_rate * kStep);
        const double mid = heading + 0.5 * curvature * kStep;
        p += kStep * Eigen::Vector2d(std::cos(mid), std::sin(mid));
        heading += curvature * kStep;
        s += kStep;
    }
    // Speed allowed by the geometry, then held over +-window so the speed is constant through a blend.
    const std::size_t m = kappa.size();
    std::vector<double> raw(m, config.cruise_speed);
    for (std::size_t i = 0; i < m; ++i) {
        const double k = std::abs(kappa[i]);
        const std::size_t a = i >= 5 ? i - 5 : 0, b = std::min(m - 1, i + 5);
        const double rate = b > a ? std::abs(kappa[b] - kappa[a]) / ((b - a) * kStep) : 0.0;
        if (k > 1e-9) raw[i] = std::min({raw[i], std::sqrt(config.max_lateral_accel / k), config.max_yaw_rate / k});
        if (rate > 1e-9) raw[i] = std::min(raw[i], std::sqrt(config.max_yaw_accel / rate));
    }
    const std::size_t window = static_cast<std::size_t>(3.0 / kStep);
    track.limit.assign(m, config.cruise_speed);
    for (std::size_t i = 0; i < m; ++i)
        for (std::size_t j = i >= window ? i - window : 0; j < std::min(m, i + window + 1); ++j)
            track.limit[i] = std::min(track.limit[i], raw[j]);
    return track;
}

/// Speed at every vertex: the geometric limit, the start speed, then acceleration and deceleration limits.
std::vector<double> SpeedProfile(const Track& track, const MotionConfig& config) {
    const std::size_t n = track.s.size();
    std::vector<double> speed = track.limit;
    speed[0] = std::min(speed[0], config.start_speed);
    for (std::size_t i = 1; i < n; ++i)
        speed[i] = std::min(speed[i], std::sqrt(speed[i - 1] * speed[i - 1] + 2.0 * config.max_accel * (track.s[i] - track.s[i - 1])));
    for (std::size_t i = n - 1; i-- > 0;)
        speed[i] = std::min(speed[i], std::sqrt(speed[i + 1] * speed[i + 1] + 2.0 * config.max_decel * (track.s[i + 1] - track.s[i])));
    return speed;
}

std::vector<double> TimesOf(const Track& track, const std::vector<double>& speed) {
    std::vector<double> time(track.s.size(), 0.0);
    for (std::size_t i = 1; i < time.size(); ++i)
        time[i] = time[i - 1] + (track.s[i] - track.s[i - 1]) / std::max(0.5 * (speed[i] + speed[i - 1]), 0.2);
    return time;
}

/// A sample of the track at time t: position, heading and the vertex just after it.
struct Sample {
    Eigen::Vector2d position;
    double heading = 0.0;
    std::size_t vertex = 0;
};

std::vector<Sample> SampleAtRate(const Track& track, const std::vector<double>& time, double rate) {
    std::vector<Sample> samples;
    const std::size_t n = time.size();
    std::size_t i = 1;
    for (std::size_t k = 0;; ++k) {
        const double t = k / rate;
        if (t > time.back()) break;
        while (i + 1 < n && time[i] < t) ++i;
        const double f = std::clamp((t - time[i - 1]) / std::max(time[i] - time[i - 1], 1e-9), 0.0, 1.0);
        samples.push_back({track.position[i - 1] + f * (track.position[i] - track.position[i - 1]),
                           track.heading[i - 1] + f * (track.heading[i] - track.heading[i - 1]), i});
    }
    return samples;
}

/// Lowers the speed limit where the sampled yaw rate or its change still exceeds the limits (the
/// acceleration out of a blend, kappa * dv/dt, is not covered by the geometric limit). True if none did.
bool SlowDownWhereYawTooFast(const std::vector<Sample>& samples, const MotionConfig& config, Track& track) {
    const double margin = 0.97;
    std::vector<bool> slow(track.limit.size(), false);
    bool ok = true;
    auto mark = [&](std::size_t from, std::size_t to) {
        const std::size_t pad = static_cast<std::size_t>(3.0 / kStep);
        for (std::size_t v = from >= pad ? from - pad : 0; v < std::min(slow.size(), to + pad + 1); ++v) slow[v] = true;
        ok = false;
    };
    double previous_rate = 0.0;
    for (std::size_t k = 1; k < samples.size(); ++k) {
        const double yaw_rate = (samples[k].heading - samples[k - 1].heading) * config.rate;
        if (std::abs(yaw_rate) > margin * config.max_yaw_rate) mark(samples[k - 1].vertex, samples[k].vertex);
        if (k >= 2 && std::abs(yaw_rate - previous_rate) * config.rate > margin * config.max_yaw_accel)
            mark(samples[k - 2].vertex, samples[k].vertex);
        previous_rate = yaw_rate;
    }
    for (std::size_t v = 0; v < slow.size(); ++v)
        if (slow[v]) track.limit[v] = std::max(0.5, 0.9 * track.limit[v]);
    return ok;
}

}  // namespace

Trajectory DrivePath(const std::vector<Eigen::Vector2d>& path, const Ground& ground, const MotionConfig& config,
                     std::uint64_t seed) {
    Trajectory trajectory;
    if (path.size() < 2) return trajectory;
    const bool steering = config.min_turn_radius > 0.0;
    Track track = steering ? FollowWithSteering(path, config) : FollowAsGiven(path, config);
    if (track.s.size() < 2) return trajectory;
    std::vector<Sample> samples;
    for (int iteration = 0; iteration < 40; ++iteration) {
        samples = SampleAtRate(track, TimesOf(track, SpeedProfile(track, config)), config.rate);
        if (!steering || SlowDownWhereYawTooFast(samples, config, track)) break;
    }

    std::mt19937 rng(static_cast<std::uint32_t>(seed * 9176u + 3u));
    std::uniform_real_distribution<double> phase(0.0, kTwoPi);
    const double phase_pitch = phase(rng), phase_roll = phase(rng), phase_yaw = phase(rng);
    const Eigen::Isometry3d T_vehicle_mount =
        PoseFromXYZRPY(0.0, 0.0, config.mount_height, config.mount_roll, config.mount_pitch, config.mount_yaw);
    for (std::size_t k = 0; k < samples.size(); ++k) {
        const double t = k / config.rate;
        const Eigen::Vector2d p = samples[k].position;
        const Eigen::Vector2d direction(std::cos(samples[k].heading), std::sin(samples[k].heading));
        const Eigen::Vector2d g = ground.Gradient(p.x(), p.y());
        const double slope_forward = g.dot(direction);
        const double slope_left = g.dot(Eigen::Vector2d(-direction.y(), direction.x()));
        const Eigen::Isometry3d T_world_vehicle = PoseFromXYZRPY(p.x(), p.y(), ground.Height(p.x(), p.y()),
                                                                 std::atan(slope_left), -std::atan(slope_forward),
                                                                 std::remainder(samples[k].heading, kTwoPi));
        Eigen::Isometry3d T_vehicle_sensor = T_vehicle_mount;
        if (config.handheld) {
            const double w = kTwoPi * config.step_frequency;
            const Eigen::Isometry3d sway = PoseFromXYZRPY(
                0.0, 0.0, config.bob_amplitude * std::sin(w * t), config.sway_roll * std::sin(0.5 * w * t + phase_roll),
                config.sway_pitch * std::sin(0.23 * w * t + phase_pitch), config.sway_yaw * std::sin(0.11 * w * t + phase_yaw));
            T_vehicle_sensor = T_vehicle_mount * sway;
        }
        trajectory.timestamps.push_back(t);
        trajectory.poses.push_back(T_world_vehicle * T_vehicle_sensor);
    }
    return trajectory;
}

}  // namespace revisit
