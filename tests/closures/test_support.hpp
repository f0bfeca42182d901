#pragma once
/// Test fixtures for the closure module: real KITTI local maps and synthetic box worlds.
#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "closures/local_map.hpp"
#include "core/se3.hpp"

namespace revisit::test {

inline std::filesystem::path KittiDir() { return std::filesystem::path(REVISIT_SHARED_DIR) / "data" / "kitti00_first16"; }
inline bool HaveKitti() { return std::filesystem::exists(KittiDir() / "velodyne" / "000000.bin"); }

inline Eigen::Isometry3d ParsePose34(const std::string& line, std::size_t skip_tokens = 0) {
    std::istringstream s(line);
    std::string token;
    for (std::size_t i = 0; i < skip_tokens; ++i) s >> token;
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 4; ++c) s >> T.matrix()(r, c);
    return T;
}

/// Lidar-frame ground-truth poses: Tr^-1 * P * Tr (METHOD.md section 1).
inline std::vector<Eigen::Isometry3d> KittiLidarPoses() {
    std::ifstream calib(KittiDir() / "calib.txt");
    std::string line;
    Eigen::Isometry3d Tr = Eigen::Isometry3d::Identity();
    while (std::getline(calib, line)) {
        if (line.rfind("Tr:", 0) == 0) Tr = ParsePose34(line, 1);
    }
    std::ifstream poses(KittiDir() / "poses.txt");
    std::vector<Eigen::Isometry3d> result;
    while (std::getline(poses, line)) {
        if (!line.empty()) result.push_back(Tr.inverse() * ParsePose34(line) * Tr);
    }
    return result;
}

/// One KITTI scan, cropped to [min_range, max_range].
inline std::vector<Eigen::Vector3f> KittiScan(int index, float min_range = 5.f, float max_range = 100.f) {
    char name[32];
    std::snprintf(name, sizeof(name), "%06d.bin", index);
    std::ifstream in(KittiDir() / "velodyne" / name, std::ios::binary);
    std::vector<float> raw;
    float values[4];
    std::vector<Eigen::Vector3f> points;
    while (in.read(reinterpret_cast<char*>(values), sizeof(values))) {
        const Eigen::Vector3f p(values[0], values[1], values[2]);
        const float r = p.norm();
        if (r >= min_range && r <= max_range) points.push_back(p);
    }
    return points;
}

/// Local maps of KITTI frames [first, last] with ground-truth poses (one map, never split).
inline LocalMap KittiLocalMap(int first, int last, int id) {
    const auto poses = KittiLidarPoses();
    LocalMapConfig config;
    config.split_distance = 1e9;
    LocalMapper mapper(config);
    for (int i = first; i <= last; ++i) mapper.AddScan(std::size_t(i), KittiScan(i), poses[std::size_t(i)]);
    auto map = *mapper.Finish();
    map.id = id;
    return map;
}

/// A synthetic world: boxes (buildings, poles) with sampled visible surfaces and a flat ground.
struct SurfacePoint {
    Eigen::Vector3f position;
    Eigen::Vector2f normal;  ///< outward horizontal normal; zero for ground
};

inline std::vector<SurfacePoint> MakeBoxWorld(std::uint32_t seed, double half_extent = 120.0, int num_boxes = 90,
                                              double size_scale = 1.0, double points_per_m2 = 6.0) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> pos(-half_extent, half_extent), angle(-M_PI, M_PI), unit(0.0, 1.0);
    std::vector<SurfacePoint> world;
    for (int b = 0; b < num_boxes; ++b) {
        const bool pole = unit(rng) < 0.3;
        const double sx = pole ? 0.4 : size_scale * (2.0 + 14.0 * unit(rng));
        const double sy = pole ? 0.4 : size_scale * (2.0 + 14.0 * unit(rng));
        const double height = pole ? 6.0 : 3.0 + 10.0 * unit(rng);
        const Eigen::Vector2d center(pos(rng), pos(rng));
        const Eigen::Rotation2Dd R(angle(rng));
        const Eigen::Vector2d corners[4] = {{-sx / 2, -sy / 2}, {sx / 2, -sy / 2}, {sx / 2, sy / 2}, {-sx / 2, sy / 2}};
        for (int f = 0; f < 4; ++f) {
            const Eigen::Vector2d a = center + R * corners[f], c = center + R * corners[(f + 1) % 4];
            const Eigen::Vector2d edge = c - a;
            const Eigen::Vector2d normal = Eigen::Vector2d(edge.y(), -edge.x()).normalized();
            const int n = int(std::ceil(edge.norm() * height * points_per_m2));
            for (int k = 0; k < n; ++k) {
                const Eigen::Vector2d xy = a + unit(rng) * edge;
                world.push_back({Eigen::Vector3f(float(xy.x()), float(xy.y()), float(unit(rng) * height)),
                                 normal.cast<float>()});
            }
        }
    }
    for (double x = -half_extent - 40; x <= half_extent + 40; x += 1.0)
        for (double y = -half_extent - 40; y <= half_extent + 40; y += 1.0)
            world.push_back({Eigen::Vector3f(float(x + unit(rng)), float(y + unit(rng)), 0.f), Eigen::Vector2f::Zero()});
    return world;
}

/// A local map seen along a route of sensor positions: points within `range` of a route position whose
/// face looks toward it, in the frame of the first route pose (sensor 1.8 m above the ground), with noise.
inline LocalMap SimulateLocalMap(const std::vector<SurfacePoint>& world, const std::vector<Eigen::Isometry3d>& route,
                                 int id, std::uint32_t seed, double range = 60.0) {
    std::mt19937 rng(seed);
    std::normal_distribution<float> noise(0.f, 0.03f);
    LocalMap map;
    map.id = id;
    map.T_world_map = route.front();
    const Eigen::Isometry3f T_map_world = route.front().inverse().cast<float>();
    for (const auto& s : world) {
        for (const auto& pose : route) {
            const Eigen::Vector2f to_sensor = pose.translation().head<2>().cast<float>() - s.position.head<2>();
            if (to_sensor.norm() > range || to_sensor.dot(s.normal) < 0.f) continue;
            map.points.push_back(T_map_world * s.position + Eigen::Vector3f(noise(rng), noise(rng), noise(rng)));
            break;
        }
    }
    for (const auto& pose : route) map.T_map_scan.push_back(route.front().inverse() * pose);
    return map;
}

/// A straight route of `n` poses from (x, y) with heading `yaw`, `step` metres apart, sensor 1.8 m up.
inline std::vector<Eigen::Isometry3d> StraightRoute(double x, double y, double yaw, int n = 10, double step = 2.0) {
    std::vector<Eigen::Isometry3d> route;
    for (int i = 0; i < n; ++i) {
        Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
        T.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
        T.translation() = Eigen::Vector3d(x + i * step * std::cos(yaw), y + i * step * std::sin(yaw), 1.8);
        route.push_back(T);
    }
    return route;
}

/// Moves a map's points into another frame: the result's points are T_new_old * points.
inline LocalMap Transformed(const LocalMap& map, const Eigen::Isometry3d& T_new_old, int id) {
    LocalMap out = map;
    out.id = id;
    const Eigen::Isometry3f T = T_new_old.cast<float>();
    for (auto& p : out.points) p = T * p;
    return out;
}

inline double YawError(const Eigen::Matrix4d& estimate, const Eigen::Isometry3d& truth) {
    const Eigen::Matrix3d R = truth.linear().transpose() * estimate.topLeftCorner<3, 3>();
    return std::abs(std::atan2(R(1, 0), R(0, 0)));
}

inline double TranslationError(const Eigen::Matrix4d& estimate, const Eigen::Isometry3d& truth) {
    return (estimate.topRightCorner<3, 1>() - truth.translation()).head<2>().norm();
}

}  // namespace revisit::test
