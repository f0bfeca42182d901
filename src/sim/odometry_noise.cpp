#include "sim/odometry_noise.hpp"

#include <cmath>
#include <random>

#include "core/se3.hpp"

namespace revisit {

Poses SimulateOdometry(const Trajectory& ground_truth, const OdometryNoiseConfig& config, std::uint64_t seed) {
    Poses odometry;
    if (ground_truth.empty()) return odometry;
    std::mt19937_64 rng(seed * 0x2545F4914F6CDD1DULL + 99u);
    std::normal_distribution<double> normal(0.0, 1.0);
    odometry.push_back(ground_truth.poses.front());
    double yaw_bias = config.yaw_rate_bias;
    for (std::size_t k = 1; k < ground_truth.size(); ++k) {
        const double dt = ground_truth.has_timestamps() ? ground_truth.timestamps[k] - ground_truth.timestamps[k - 1] : 0.1;
        const Eigen::Isometry3d delta = ground_truth.poses[k - 1].inverse() * ground_truth.poses[k];
        Vector6d noise = Vector6d::Zero();
        for (int a = 0; a < 3; ++a) noise[a] = config.translation_noise * normal(rng);
        for (int a = 3; a < 6; ++a) noise[a] = config.rotation_noise * normal(rng);
        yaw_bias += config.yaw_bias_random_walk * std::sqrt(std::max(dt, 0.0)) * normal(rng);
        noise[5] += yaw_bias * dt;  // gyro bias integrates about the sensor's z axis
        Eigen::Isometry3d noisy = delta;
        noisy.translation() *= 1.0 + config.speed_scale_bias;
        odometry.push_back(odometry.back() * noisy * ExpSE3(noise));
    }
    return odometry;
}

}  // namespace revisit
