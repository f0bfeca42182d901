#pragma once
/// Pose-graph fixtures: a city route with revisits, drifting odometry, true and false
/// closures, and APE after SE(3) alignment (Umeyama without scale, as evo computes it).
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "core/se3.hpp"
#include "core/trajectory.hpp"
#include "optimization/pose_graph.hpp"

namespace revisit::testing {

/// Drives straight segments joined by 90-degree arcs of 10 m radius, sampling every `step` metres.
/// Commands: {length_m, turn}: drive length_m straight, then turn (+1 left, -1 right, 0 none).
inline Poses DriveRoute(const std::vector<std::pair<double, int>>& commands, double step) {
    Poses route;
    Eigen::Vector2d position(0.0, 0.0);
    double heading = 0.0;
    auto emit = [&]() {
        // Gentle hills so that the problem is really 3D.
        const double z = 4.0 * std::sin(position.x() / 180.0) + 2.0 * std::cos(position.y() / 130.0);
        route.push_back(PoseFromXYZRPY(position.x(), position.y(), z, 0.0, 0.0, heading));
    };
    const double radius = 10.0;
    for (const auto& [length, turn] : commands) {
        for (double s = 0.0; s < length; s += step) {
            emit();
            position += step * Eigen::Vector2d(std::cos(heading), std::sin(heading));
        }
        if (turn == 0) continue;
        const int arc_steps = static_cast<int>(std::round(M_PI / 2.0 * radius / step));
        const double arc_step = M_PI / 2.0 / arc_steps;  // exactly 90 degrees, so the loops close
        for (int k = 0; k < arc_steps; ++k) {
            emit();
            heading += turn * arc_step;
            position += step * Eigen::Vector2d(std::cos(heading), std::sin(heading));
        }
    }
    return route;
}

/// ~4.6 km: an outer 600 x 400 m block, its west half, then the east half partly against the
/// first direction: most streets are revisited, some in the opposite direction. Nodes every `node_spacing` metres.
inline Poses CityRoute(double node_spacing) {
    const double step = 0.5;
    const Poses fine = DriveRoute({{580, 1}, {380, 1}, {580, 1}, {380, 1},    // outer loop (arcs add 10 m per side)
                                   {280, 1}, {380, 1}, {280, 1}, {380, 1},    // west half, same direction
                                   {280, 1}, {180, -1}, {280, -1}, {180, -1},  // middle street, east side southwards
                                   {300, 0}},                                 // back west along the first street
                      step);
    Poses nodes;
    const auto stride = static_cast<std::size_t>(std::max(1.0, std::round(node_spacing / step)));
    for (std::size_t i = 0; i < fine.size(); i += stride) nodes.push_back(fine[i]);
    return nodes;
}

struct DriftModel {
    double yaw_bias = 1.5e-4;       ///< [rad/m] systematic heading drift
    double scale_error = 0.01;      ///< relative distance error (1%)
    double sigma_translation = 0.02;  ///< [m/sqrt(m)] random walk per metre travelled
    double sigma_rotation = 2e-4;     ///< [rad/sqrt(m)]
    std::uint32_t seed = 5;
};

/// Odometry: true increments scaled, biased and perturbed, integrated from the first pose.
inline Poses DriftingOdometry(const Poses& truth, const DriftModel& model) {
    std::mt19937 rng(model.seed);
    std::normal_distribution<double> normal(0.0, 1.0);
    Poses odometry = {truth.front()};
    for (std::size_t i = 1; i < truth.size(); ++i) {
        Eigen::Isometry3d step = truth[i - 1].inverse() * truth[i];
        const double distance = step.translation().norm();
        step.translation() *= 1.0 + model.scale_error;
        Vector6d noise;
        const double sq = std::sqrt(distance);
        noise << model.sigma_translation * sq * normal(rng), model.sigma_translation * sq * normal(rng),
            model.sigma_translation * sq * normal(rng), model.sigma_rotation * sq * normal(rng),
            model.sigma_rotation * sq * normal(rng), model.yaw_bias * distance + model.sigma_rotation * sq * normal(rng);
        odometry.push_back(odometry.back() * step * ExpSE3(noise));
    }
    return odometry;
}

/// True closures: for each node, the nearest earlier node closer than `max_distance` [m]
/// and at least `min_travel` [m] of travel before; measured with small noise. At most one
/// closure every `every` nodes.
inline std::vector<PoseGraphEdge> TrueClosures(const Poses& truth, double max_distance, double min_travel, int every,
                                               const Matrix6d& information, std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::normal_distribution<double> normal(0.0, 1.0);
    const auto travel = CumulativeDistance(truth);
    std::vector<PoseGraphEdge> closures;
    int last = -every;
    for (int j = 0; j < static_cast<int>(truth.size()); ++j) {
        if (j - last < every) continue;
        int best = -1;
        double best_distance = max_distance;
        for (int i = 0; i < j; ++i) {
            if (travel[j] - travel[i] < min_travel) break;
            const double distance = (truth[i].translation() - truth[j].translation()).norm();
            if (distance < best_distance) {
                best_distance = distance;
                best = i;
            }
        }
        if (best < 0) continue;
        Vector6d noise;
        noise << 0.05 * normal(rng), 0.05 * normal(rng), 0.05 * normal(rng), 0.003 * normal(rng), 0.003 * normal(rng),
            0.003 * normal(rng);
        closures.push_back({j, best, truth[j].inverse() * truth[best] * ExpSE3(noise), information, true});
        last = j;
    }
    return closures;
}

/// Wrong closures between places at least `min_distance` [m] apart, each with a plausible
/// measured pose (a few metres and degrees, as a real closure would have).
inline std::vector<PoseGraphEdge> FalseClosures(const Poses& truth, int count, double min_distance,
                                                const Matrix6d& information, std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_int_distribution<int> node(0, static_cast<int>(truth.size()) - 1);
    std::uniform_real_distribution<double> offset(-3.0, 3.0);
    std::uniform_real_distribution<double> yaw(-0.2, 0.2);
    std::vector<PoseGraphEdge> closures;
    while (static_cast<int>(closures.size()) < count) {
        const int a = node(rng);
        const int b = node(rng);
        if ((truth[a].translation() - truth[b].translation()).norm() < min_distance) continue;
        closures.push_back({std::max(a, b), std::min(a, b), PoseFromXYZRPY(offset(rng), offset(rng), 0.0, 0.0, 0.0, yaw(rng)),
                            information, true});
    }
    return closures;
}

/// KITTI ground truth (3x4, left camera: x right, y down, z forward) turned z-up, one pose every
/// `spacing` metres of travel. Empty when the file is missing.
inline Poses ReadKittiRoute(const std::filesystem::path& file, double spacing) {
    std::ifstream in(file);
    Eigen::Matrix3d camera_to_z_up;
    camera_to_z_up << 0, 0, 1, -1, 0, 0, 0, -1, 0;
    Eigen::Isometry3d C = Eigen::Isometry3d::Identity();
    C.linear() = camera_to_z_up;
    Poses route;
    std::string line;
    while (std::getline(in, line)) {
        std::istringstream fields(line);
        Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
        for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 4; ++c) fields >> T.matrix()(r, c);
        T.linear() = NearestRotation(T.linear());
        const Eigen::Isometry3d T_z_up = C * T * C.inverse();
        if (route.empty() || (T_z_up.translation() - route.back().translation()).norm() >= spacing) route.push_back(T_z_up);
    }
    return route;
}

/// APE translation RMSE [m] after aligning `estimate` onto `truth` with SE(3) Umeyama (no scale).
inline double ApeTranslationRmse(const Poses& estimate, const Poses& truth) {
    Eigen::Matrix3Xd source(3, estimate.size());
    Eigen::Matrix3Xd target(3, truth.size());
    for (std::size_t i = 0; i < estimate.size(); ++i) {
        source.col(static_cast<Eigen::Index>(i)) = estimate[i].translation();
        target.col(static_cast<Eigen::Index>(i)) = truth[i].translation();
    }
    const Eigen::Matrix4d alignment = Eigen::umeyama(source, target, false);
    const Eigen::Matrix3Xd aligned = (alignment.topLeftCorner<3, 3>() * source).colwise() + alignment.topRightCorner<3, 1>();
    return std::sqrt((aligned - target).colwise().squaredNorm().mean());
}

}  // namespace revisit::testing
