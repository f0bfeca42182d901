#include "synthetic_world.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "core/se3.hpp"

namespace revisit::test {

Eigen::Vector3d Box::Unrotate(const Eigen::Vector3d& p) const {
    const Eigen::Vector3d centre = 0.5 * (lo + hi);
    return centre + Eigen::AngleAxisd(-yaw, Eigen::Vector3d::UnitZ()) * (p - centre);
}

std::vector<Eigen::Vector2d> Box::Corners() const {
    const Eigen::Vector3d centre = 0.5 * (lo + hi);
    std::vector<Eigen::Vector2d> corners;
    for (int c = 0; c < 4; ++c) {
        const Eigen::Vector3d corner((c & 1) ? hi.x() : lo.x(), (c & 2) ? hi.y() : lo.y(), 0.0);
        corners.push_back((centre + Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) * (corner - centre)).head<2>());
    }
    return corners;
}

namespace {

double Deg(double degrees) { return degrees * M_PI / 180.0; }

/// A box ready for ray tests: its rotation precomputed.
struct PreparedBox {
    Eigen::Vector3d lo, hi, centre;
    double c = 1.0, s = 0.0;  ///< cos and sin of -yaw
    explicit PreparedBox(const Box& box)
        : lo(box.lo), hi(box.hi), centre(0.5 * (box.lo + box.hi)), c(std::cos(box.yaw)), s(-std::sin(box.yaw)) {}
    Eigen::Vector3d Rotate(const Eigen::Vector3d& v) const { return {c * v.x() - s * v.y(), s * v.x() + c * v.y(), v.z()}; }
};

/// Slab test in the box's frame; the entry distance along the ray, or infinity.
double HitBox(const PreparedBox& box, const Eigen::Vector3d& world_origin, const Eigen::Vector3d& world_direction) {
    const Eigen::Vector3d origin = box.centre + box.Rotate(world_origin - box.centre);
    const Eigen::Vector3d direction = box.Rotate(world_direction);
    double t_near = 0.0;
    double t_far = std::numeric_limits<double>::infinity();
    for (int a = 0; a < 3; ++a) {
        if (std::abs(direction[a]) < 1e-12) {
            if (origin[a] < box.lo[a] || origin[a] > box.hi[a]) return std::numeric_limits<double>::infinity();
            continue;
        }
        double t0 = (box.lo[a] - origin[a]) / direction[a];
        double t1 = (box.hi[a] - origin[a]) / direction[a];
        if (t0 > t1) std::swap(t0, t1);
        t_near = std::max(t_near, t0);
        t_far = std::min(t_far, t1);
        if (t_near > t_far) return std::numeric_limits<double>::infinity();
    }
    return t_near > 0.0 ? t_near : std::numeric_limits<double>::infinity();
}

bool BoxClearOfRoute(const Poses& route, const Box& box, double clearance) {
    // Distance from the route's poses to the box footprint.
    for (const auto& T : route) {
        const Eigen::Vector2d p = box.Unrotate(T.translation()).head<2>();
        const Eigen::Vector2d closest = p.cwiseMax(box.lo.head<2>()).cwiseMin(box.hi.head<2>());
        if ((closest - p).norm() < clearance) return false;
    }
    return true;
}

}  // namespace

RayPattern SpinningPattern(int beams, int columns, double min_elevation_deg, double max_elevation_deg, double max_range) {
    RayPattern pattern;
    pattern.max_range = max_range;
    for (int c = 0; c < columns; ++c) {
        const double azimuth = M_PI - 2.0 * M_PI * (c + 0.5) / columns;  // clockwise from behind
        for (int b = 0; b < beams; ++b) {
            const double elevation =
                Deg(min_elevation_deg + (max_elevation_deg - min_elevation_deg) * b / std::max(1, beams - 1));
            pattern.directions.emplace_back(std::cos(elevation) * std::cos(azimuth),
                                            std::cos(elevation) * std::sin(azimuth), std::sin(elevation));
            pattern.sweep_times.push_back(0.5 * (1.0 - azimuth / M_PI));
        }
    }
    return pattern;
}

RayPattern RosettePattern(int rays, double fov_deg, double max_range) {
    RayPattern pattern;
    pattern.max_range = max_range;
    const double half = Deg(fov_deg) / 2.0;
    for (int i = 0; i < rays; ++i) {
        const double u = static_cast<double>(i) / rays;
        // Rose curve r = cos(k theta), with a slow precession so the pattern fills the cone.
        const double theta = 2.0 * M_PI * 37.0 * u;
        const double r = half * std::abs(std::cos(3.3 * theta));
        const double phi = theta + 2.0 * M_PI * u;
        const double y = std::tan(r) * std::cos(phi);
        const double z = std::tan(r) * std::sin(phi);
        pattern.directions.push_back(Eigen::Vector3d(1.0, y, z).normalized());
        pattern.sweep_times.push_back(u);
    }
    return pattern;
}

RayPattern PlanarPattern(int beams, double fov_deg, double max_range) {
    RayPattern pattern;
    pattern.max_range = max_range;
    for (int i = 0; i < beams; ++i) {
        const double angle = Deg(-fov_deg / 2.0 + fov_deg * (i + 0.5) / beams);
        pattern.directions.emplace_back(std::cos(angle), std::sin(angle), 0.0);
        pattern.sweep_times.push_back(static_cast<double>(i) / beams);
    }
    return pattern;
}

World MakeCity(const Poses& route, double clearance, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    auto uniform = [&](double lo, double hi) { return lo + (hi - lo) * unit(rng); };
    World world;
    // Every object gets its own orientation: walls parallel to the route would look the same from
    // everywhere along it (as flat ground does), which real streets rarely do for long.
    auto place = [&](const Eigen::Vector2d& c, double sx, double sy, double sz) {
        const Box box{Eigen::Vector3d(c.x() - sx / 2, c.y() - sy / 2, 0.0), Eigen::Vector3d(c.x() + sx / 2, c.y() + sy / 2, sz),
                      uniform(-M_PI, M_PI)};
        if (BoxClearOfRoute(route, box, clearance)) world.boxes.push_back(box);
    };
    // A street: building rows, parked cars and poles on both sides of the route, continued 60 m
    // beyond both of its ends (the sensor sees that far).
    Poses street;
    for (int k = 60; k > 0; --k) street.push_back(route.front() * Eigen::Isometry3d(Eigen::Translation3d(-1.0 * k, 0.0, 0.0)));
    street.insert(street.end(), route.begin(), route.end());
    for (int k = 1; k <= 60; ++k) street.push_back(route.back() * Eigen::Isometry3d(Eigen::Translation3d(1.0 * k, 0.0, 0.0)));
    double travelled = 0.0, next_item = 0.0;
    for (std::size_t i = 1; i < street.size(); ++i) {
        travelled += (street[i].translation() - street[i - 1].translation()).norm();
        if (travelled < next_item) continue;
        next_item = travelled + uniform(2.0, 5.0);
        const Eigen::Vector2d p = street[i].translation().head<2>();
        const Eigen::Vector2d left = street[i].linear().col(1).head<2>().normalized();
        for (const double side : {-1.0, 1.0}) {
            // Curb: a low step that, unlike the flat road, does not move with the sensor.
            const Eigen::Vector2d curb = p + side * left * (clearance - 0.5);
            const Box curb_box{Eigen::Vector3d(curb.x() - 0.6, curb.y() - 0.6, 0.0), Eigen::Vector3d(curb.x() + 0.6, curb.y() + 0.6, 0.15)};
            if (BoxClearOfRoute(route, curb_box, clearance - 1.2)) world.boxes.push_back(curb_box);
            const double kind = unit(rng);
            if (kind < 0.45) {
                const double size = uniform(5.0, 15.0);
                place(p + side * left * (clearance + 3.0 + size / 2 + uniform(0.0, 8.0)), size, uniform(5.0, 15.0), uniform(4.0, 25.0));
            } else if (kind < 0.75) {
                place(p + side * left * (clearance + 1.0), uniform(1.6, 4.5), uniform(1.6, 4.5), uniform(1.3, 1.9));
            } else {
                place(p + side * left * (clearance + 0.5), 0.3, 0.3, uniform(4.0, 8.0));
            }
        }
    }
    // Ground clutter (kerbs, bumps, low vegetation): a real road is not a perfect plane, and a
    // perfect plane makes every ring of a spinning sensor look the same from everywhere.
    for (std::size_t i = 0; i < route.size(); ++i) {
        for (int k = 0; k < 3; ++k) {
            const Eigen::Vector2d c = route[i].translation().head<2>() +
                                      Eigen::Vector2d(uniform(-50.0, 50.0), uniform(-50.0, 50.0));
            place(c, uniform(0.3, 2.0), uniform(0.3, 2.0), uniform(0.05, 0.4));
        }
    }
    // Scattered structure farther away.
    Eigen::Vector2d lo = Eigen::Vector2d::Constant(1e9), hi = Eigen::Vector2d::Constant(-1e9);
    for (const auto& T : route) {
        lo = lo.cwiseMin(T.translation().head<2>());
        hi = hi.cwiseMax(T.translation().head<2>());
    }
    lo.array() -= 60.0;
    hi.array() += 60.0;
    const int count = static_cast<int>((hi - lo).prod() / 300.0);
    for (int k = 0; k < count; ++k) {
        place(Eigen::Vector2d(uniform(lo.x(), hi.x()), uniform(lo.y(), hi.y())), uniform(3.0, 18.0), uniform(3.0, 18.0),
              uniform(4.0, 25.0));
    }
    return world;
}

World MakeIndoor(const Poses& route, double size, double clearance, unsigned seed) {
    std::mt19937 rng(seed);
    World world;
    world.has_ground = false;
    const double t = 0.15;  // wall thickness
    auto wall = [&](double x0, double y0, double x1, double y1) {
        const Box box{Eigen::Vector3d(std::min(x0, x1) - t, std::min(y0, y1) - t, -1.0),
                      Eigen::Vector3d(std::max(x0, x1) + t, std::max(y0, y1) + t, 3.0)};
        if (BoxClearOfRoute(route, box, clearance)) world.boxes.push_back(box);
    };
    wall(-size / 2, -size / 2, size / 2, -size / 2);
    wall(-size / 2, size / 2, size / 2, size / 2);
    wall(-size / 2, -size / 2, -size / 2, size / 2);
    wall(size / 2, -size / 2, size / 2, size / 2);
    std::uniform_real_distribution<double> u(-size / 2, size / 2), len(1.0, 6.0), furniture(0.3, 1.2);
    for (int i = 0; i < 40; ++i) {
        const double x = u(rng), y = u(rng);
        if (i % 2 == 0) wall(x, y, x + len(rng), y);
        else wall(x, y, x, y + len(rng));
    }
    for (int i = 0; i < 60; ++i) {
        const double x = u(rng), y = u(rng), s = furniture(rng);
        const Box box{Eigen::Vector3d(x, y, -1.0), Eigen::Vector3d(x + s, y + s * 0.7, 1.0)};
        if (BoxClearOfRoute(route, box, clearance)) world.boxes.push_back(box);
    }
    return world;
}

Scan CastScan(const World& world, const RayPattern& pattern,
              const std::function<Eigen::Isometry3d(double)>& T_world_sensor_at, double range_noise, unsigned seed) {
    std::mt19937 rng(seed);
    std::normal_distribution<double> noise(0.0, range_noise);
    // Bin the boxes that can be hit by the azimuth interval they cover from the sweep's centre
    // (with a margin for the sensor's motion during the sweep), so a ray tests only its bin.
    constexpr int kBins = 720;
    constexpr double kMotionMargin = 3.0;  // [m]
    const Eigen::Vector2d centre = T_world_sensor_at(0.5).translation().head<2>();
    std::vector<PreparedBox> prepared;
    std::vector<std::vector<std::size_t>> bins(kBins);
    auto bin_of = [](double azimuth) {
        const int b = static_cast<int>(std::floor((azimuth + M_PI) / (2.0 * M_PI) * kBins));
        return ((b % kBins) + kBins) % kBins;
    };
    for (const auto& box : world.boxes) {
        const Eigen::Vector2d centre_in_box = box.Unrotate(Eigen::Vector3d(centre.x(), centre.y(), 0.0)).head<2>();
        const double distance = (centre_in_box.cwiseMax(box.lo.head<2>()).cwiseMin(box.hi.head<2>()) - centre_in_box).norm();
        if (distance > pattern.max_range + kMotionMargin) continue;
        prepared.emplace_back(box);
        const std::size_t index = prepared.size() - 1;
        if (distance < kMotionMargin + 1.0) {
            for (auto& bin : bins) bin.push_back(index);
            continue;
        }
        const Eigen::Vector2d mid = 0.5 * (box.lo + box.hi).head<2>() - centre;
        const double mid_azimuth = std::atan2(mid.y(), mid.x());
        double lo = 0.0, hi = 0.0;
        for (const Eigen::Vector2d& corner : box.Corners()) {
            const Eigen::Vector2d d = corner - centre;
            const double relative = std::remainder(std::atan2(d.y(), d.x()) - mid_azimuth, 2.0 * M_PI);
            lo = std::min(lo, relative);
            hi = std::max(hi, relative);
        }
        const double margin = std::asin(std::min(1.0, kMotionMargin / distance)) + 2.0 * M_PI / kBins;
        const int first = static_cast<int>(std::floor((mid_azimuth + lo - margin + M_PI) / (2.0 * M_PI) * kBins));
        const int last = static_cast<int>(std::floor((mid_azimuth + hi + margin + M_PI) / (2.0 * M_PI) * kBins));
        for (int b = first; b <= last && b < first + kBins; ++b) bins[((b % kBins) + kBins) % kBins].push_back(index);
    }
    Scan scan;
    scan.sensor_label = "SIM";
    for (std::size_t i = 0; i < pattern.directions.size(); ++i) {
        const double s = pattern.sweep_times[i];
        const Eigen::Isometry3d T = T_world_sensor_at(s);
        const Eigen::Vector3d origin = T.translation();
        const Eigen::Vector3d direction = T.linear() * pattern.directions[i];
        double range = std::numeric_limits<double>::infinity();
        if (world.has_ground && direction.z() < -1e-9) range = -origin.z() / direction.z();
        for (const std::size_t b : bins[bin_of(std::atan2(direction.y(), direction.x()))]) {
            range = std::min(range, HitBox(prepared[b], origin, direction));
        }
        if (!(range <= pattern.max_range)) continue;
        const double measured = range + (range_noise > 0.0 ? noise(rng) : 0.0);
        scan.points.push_back((measured * pattern.directions[i]).cast<float>());
        scan.point_times.push_back(static_cast<float>(0.1 * s));
    }
    return scan;
}

Poses DriveRoute(int frames, double step, double height, double yaw_rate_per_step) {
    Poses route;
    double x = 0.0, y = 0.0, yaw = 0.0;
    for (int i = 0; i < frames; ++i) {
        // Body motion of a car on its suspension: a rigid sensor gliding over a perfect plane
        // sees identical ground rings from everywhere, which no real sensor does.
        const double bounce = 0.03 * std::sin(1.3 * i);
        const double roll = 0.005 * std::sin(0.9 * i);
        const double pitch = 0.008 * std::sin(0.7 * i + 1.0);
        route.push_back(PoseFromXYZRPY(x, y, height + bounce, roll, pitch, yaw));
        // A car starting from rest at 3 m/s^2 (0.03 m per sweep per sweep at 10 Hz); the yaw rate
        // follows the speed and swings smoothly between left and right turns (an S-shape).
        const double ramp = std::min(1.0, 0.03 * (i + 1) / step);
        const double speed = step * ramp;
        yaw += ramp * yaw_rate_per_step * std::cos(3.0 * M_PI * i / std::max(1, frames));
        x += speed * std::cos(yaw);
        y += speed * std::sin(yaw);
    }
    return route;
}

}  // namespace revisit::test
