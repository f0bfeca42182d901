#include "registrability.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <unordered_map>

#include "core/se3.hpp"
#include "core/voxel.hpp"
#include "odometry/preprocess.hpp"
#include "odometry/registration.hpp"
#include "odometry/voxel_hash_map.hpp"

namespace revisit {
namespace {

// The odometry's defaults (configs/default.yaml): 1 m voxels, points in [5, 100] m.
constexpr double kVoxel = 1.0;
constexpr double kMinRange = 5.0;
constexpr double kMaxRange = 100.0;
constexpr double kDegree = 180.0 / M_PI;
using Matrix6d = Eigen::Matrix<double, 6, 6>;

double Median(std::vector<double> values) {
    if (values.empty()) return 0.0;
    std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
    return values[values.size() / 2];
}

double Percentile(std::vector<double> values, double q) {
    if (values.empty()) return 0.0;
    const std::size_t k = std::min(values.size() - 1, static_cast<std::size_t>(q * values.size()));
    std::nth_element(values.begin(), values.begin() + k, values.end());
    return values[k];
}

/// Points grouped by a 2D or 3D cell key.
template <typename Key>
std::unordered_map<long long, std::vector<Eigen::Vector3d>> Bin(const std::vector<Eigen::Vector3f>& points, double cell,
                                                                 Key&& key) {
    std::unordered_map<long long, std::vector<Eigen::Vector3d>> cells;
    for (const auto& p : points) {
        long long k = 0;
        if (key(p.cast<double>(), cell, k)) cells[k].push_back(p.cast<double>());
    }
    return cells;
}

/// Mean, eigenvalues (ascending) and eigenvectors of a point set's covariance.
Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> Shape(const std::vector<Eigen::Vector3d>& points) {
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    for (const auto& p : points) mean += p;
    mean /= static_cast<double>(points.size());
    Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
    for (const auto& p : points) covariance += (p - mean) * (p - mean).transpose();
    return Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(covariance / static_cast<double>(points.size()));
}

std::vector<Eigen::Vector3d> Source(const std::vector<Eigen::Vector3f>& scan, std::vector<Eigen::Vector3d>* map_points) {
    const auto cropped = CropRange(scan, kMinRange, kMaxRange, nullptr);
    const auto fine = VoxelDownsample(cropped, 0.5 * kVoxel);
    if (map_points != nullptr) *map_points = fine;
    return VoxelDownsample(fine, 1.5 * kVoxel);
}

/// Geman-McClure cost of the odometry (weight k^2 / (k + r^2)^2), unmatched points at the gate.
double Cost(const std::vector<Eigen::Vector3d>& source, const VoxelHashMap& map, const Eigen::Isometry3d& T, double sigma) {
    const double gate = 3.0 * sigma, kernel = sigma / 3.0;
    double cost = 0.0;
    for (const auto& p : source) {
        const Eigen::Vector3d q = T * p;
        const Eigen::Vector3d* nearest = map.FindNearest(q, gate);
        const double r2 = nearest != nullptr ? (q - *nearest).squaredNorm() : gate * gate;
        cost += 0.5 * kernel * r2 / (kernel + r2);
    }
    return cost;
}

}  // namespace

ScanStatistics DescribeScans(const ProbeSequence& sequence) {
    const double h = sequence.sensor_height;
    std::vector<double> roughness, tilts;
    double ground = 0.0, total = 0.0, scatter = 0.0, voxels = 0.0;
    for (const auto& scan : sequence.scans) {
        for (const auto& p : scan) ground += std::abs(p.z() + h) < 0.3 ? 1.0 : 0.0;
        total += static_cast<double>(scan.size());
        auto ground_key = [&](const Eigen::Vector3d& p, double cell, long long& key) {
            const double r = p.head<2>().norm();
            if (std::abs(p.z() + h) > 0.5 || r < 5.0 || r > 30.0) return false;
            key = static_cast<long long>(std::floor(p.x() / cell)) * 100003LL + static_cast<long long>(std::floor(p.y() / cell));
            return true;
        };
        for (const auto& [key, points] : Bin(scan, 1.0, ground_key)) {
            if (points.size() < 6) continue;
            const auto shape = Shape(points);
            // Two or more rings in the cell: a patch of surface, not a single ring's line.
            if (shape.eigenvalues()[1] < 0.02) continue;
            roughness.push_back(std::sqrt(std::max(shape.eigenvalues()[0], 0.0)));
        }
        for (const auto& [key, points] : Bin(scan, 4.0, ground_key)) {
            if (points.size() < 20) continue;
            const auto shape = Shape(points);
            if (shape.eigenvalues()[1] < 0.25) continue;  // a thin strip does not fix a plane
            tilts.push_back(std::acos(std::min(1.0, std::abs(shape.eigenvectors().col(0).z()))) * kDegree);
        }
        auto voxel_key = [&](const Eigen::Vector3d& p, double cell, long long& key) {
            if (p.z() + h < 0.3 || p.norm() > 40.0) return false;  // above the ground, close enough to resolve
            const Eigen::Vector3i v = (p / cell).array().floor().cast<int>();
            key = (static_cast<long long>(v.x()) * 20011LL + v.y()) * 4001LL + v.z();
            return true;
        };
        for (const auto& [key, points] : Bin(scan, 0.5, voxel_key)) {
            if (points.size() < 6) continue;
            voxels += 1.0;
            scatter += std::sqrt(std::max(Shape(points).eigenvalues()[0], 0.0)) > 0.05 ? 1.0 : 0.0;
        }
    }
    ScanStatistics stats;
    stats.ground_roughness = Median(roughness);
    double mean = 0.0, square = 0.0;
    for (double t : tilts) mean += t, square += t * t;
    if (!tilts.empty()) {
        mean /= tilts.size();
        stats.ground_tilt_spread = std::sqrt(std::max(0.0, square / tilts.size() - mean * mean));
    }
    stats.ground_share = total > 0.0 ? ground / total : 0.0;
    stats.scatter_share = voxels > 0.0 ? scatter / voxels : 0.0;
    return stats;
}

RegistrationProbe ProbeRegistration(const ProbeSequence& sequence, int history, double sigma) {
    RegistrationProbe probe;
    const double gate = 3.0 * sigma;
    std::vector<double> residuals;
    for (std::size_t k = static_cast<std::size_t>(history); k < sequence.scans.size(); ++k) {
        // The map of the predecessors at their true poses, in the frame of scan k-1 (as the odometry builds it).
        const Eigen::Isometry3d T_prev_world = sequence.poses[k - 1].inverse();
        VoxelHashMap map(kVoxel, 20);
        for (std::size_t j = k - history; j < k; ++j) {
            std::vector<Eigen::Vector3d> points;
            Source(sequence.scans[j], &points);
            const Eigen::Isometry3d T = T_prev_world * sequence.poses[j];
            for (auto& p : points) p = T * p;
            map.AddPoints(points);
        }
        const std::vector<Eigen::Vector3d> source = Source(sequence.scans[k], nullptr);
        const Eigen::Isometry3d motion = T_prev_world * sequence.poses[k];
        const double distance = motion.translation().norm();
        if (distance < 0.05) continue;
        const Eigen::Vector3d direction = motion.translation() / distance;

        // At the true pose: correspondences, residuals and the Gauss-Newton matrix sum w J^T J with
        // J = [I, -[q]x] (what the odometry solves), normalized by the number of correspondences.
        const double kernel = sigma / 3.0;
        Matrix6d H = Matrix6d::Zero();
        std::size_t matched = 0, ground = 0;
        for (const auto& p : source) {
            const Eigen::Vector3d q = motion * p;
            const Eigen::Vector3d* nearest = map.FindNearest(q, gate);
            if (nearest == nullptr) continue;
            const Eigen::Vector3d r = q - *nearest;
            residuals.push_back(r.norm());
            const double w = kernel * kernel / std::pow(kernel + r.squaredNorm(), 2);
            Eigen::Matrix<double, 3, 6> J;
            J.leftCols<3>().setIdentity();
            J.rightCols<3>() << 0.0, q.z(), -q.y(), -q.z(), 0.0, q.x(), q.y(), -q.x(), 0.0;
            H += w * J.transpose() * J;
            ++matched;
            ground += std::abs(p.z() + sequence.sensor_height) < 0.3 ? 1 : 0;
        }
        const double n = std::max<double>(1.0, static_cast<double>(matched));
        probe.correspondences += static_cast<double>(matched);
        probe.ground_correspondence_share += static_cast<double>(ground) / n;
        const auto eigen = Eigen::SelfAdjointEigenSolver<Matrix6d>(H / n).eigenvalues();
        probe.jtj_min_eigen += eigen[0];
        probe.jtj_condition += eigen[5] / std::max(eigen[0], 1e-12);
        const Matrix6d covariance = (H / n + 1e-9 * Matrix6d::Identity()).inverse();
        probe.along_information += 1.0 / std::max(direction.dot(covariance.topLeftCorner<3, 3>() * direction), 1e-12);

        // The cost along the true motion (translation and rotation scaled together).
        const Vector6d xi = LogSE3(motion);
        const double zero = Cost(source, map, Eigen::Isometry3d::Identity(), sigma);
        for (int a = 0; a < 7; ++a) {
            const double alpha = -0.5 + 0.25 * a;
            probe.cost[a] += Cost(source, map, ExpSE3(alpha * xi), sigma) / std::max(zero, 1e-12);
        }
        const double step = std::min(0.1, 0.5 * distance) / distance;
        const bool minimum = Cost(source, map, ExpSE3(step * xi), sigma) > zero &&
                             Cost(source, map, ExpSE3(-step * xi), sigma) > zero;
        probe.zero_is_local_minimum += minimum ? 1.0 : 0.0;

        // ICP from zero motion (the constant-velocity guess of a vehicle that was at rest).
        IcpParams params;
        params.max_correspondence_distance = gate;
        params.kernel = kernel;
        const IcpResult icp = RegisterPointsToMap(source, map, Eigen::Isometry3d::Identity(), params);
        probe.recovered += icp.T_world_sensor.translation().dot(direction) / distance;
        ++probe.frames;
    }
    if (probe.frames > 0) {
        const double f = probe.frames;
        probe.correspondences /= f;
        probe.ground_correspondence_share /= f;
        probe.jtj_min_eigen /= f;
        probe.jtj_condition /= f;
        probe.along_information /= f;
        for (auto& c : probe.cost) c /= f;
        probe.zero_is_local_minimum /= f;
        probe.recovered /= f;
    }
    probe.residual_median = Median(residuals);
    probe.residual_p90 = Percentile(residuals, 0.9);
    return probe;
}

}  // namespace revisit
