#include "closures/ground_alignment.hpp"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace revisit {
namespace {

std::vector<Eigen::Vector3d> LowestPerCell(const std::vector<Eigen::Vector3f>& points, double cell_size) {
    if (points.empty()) return {};
    // A dense grid over the bounding box: faster than hashing for the map sizes we see (~300 m at 1 m).
    Eigen::Vector2f lo = points.front().head<2>(), hi = lo;
    for (const auto& p : points) {
        lo = lo.cwiseMin(p.head<2>());
        hi = hi.cwiseMax(p.head<2>());
    }
    const float inv = float(1.0 / cell_size);
    const int cols = int((hi.x() - lo.x()) * inv) + 1, rows = int((hi.y() - lo.y()) * inv) + 1;
    constexpr std::int32_t kEmpty = -1;
    std::vector<std::int32_t> lowest(std::size_t(rows) * std::size_t(cols), kEmpty);
    for (std::size_t i = 0; i < points.size(); ++i) {
        const auto& p = points[i];
        const std::size_t cell = std::size_t(int((p.y() - lo.y()) * inv)) * cols + std::size_t(int((p.x() - lo.x()) * inv));
        if (lowest[cell] == kEmpty || p.z() < points[std::size_t(lowest[cell])].z()) lowest[cell] = std::int32_t(i);
    }
    std::vector<Eigen::Vector3d> result;
    for (const auto index : lowest) {
        if (index != kEmpty) result.push_back(points[std::size_t(index)].cast<double>());
    }
    return result;
}

}  // namespace

GroundAlignment AlignGround(const std::vector<Eigen::Vector3f>& points_in_map, const GroundAlignmentConfig& config) {
    GroundAlignment result;
    const auto candidates = LowestPerCell(points_in_map, config.cell_size);
    if (int(candidates.size()) < config.min_ground_points) return result;

    // Start from a level plane through the median candidate height.
    std::vector<double> heights;
    heights.reserve(candidates.size());
    for (const auto& c : candidates) heights.push_back(c.z());
    std::nth_element(heights.begin(), heights.begin() + heights.size() / 2, heights.end());
    Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
    double offset = -heights[heights.size() / 2];  // plane: normal . p + offset = 0

    int num_inliers = 0;
    for (int iteration = 0; iteration < config.iterations; ++iteration) {
        const double scale = config.iterations > 1 ? 4.0 - 3.0 * iteration / (config.iterations - 1) : 1.0;
        const double gate = config.inlier_distance * scale;
        Eigen::Vector3d mean = Eigen::Vector3d::Zero();
        Eigen::Matrix3d second = Eigen::Matrix3d::Zero();
        num_inliers = 0;
        for (const auto& c : candidates) {
            if (std::abs(normal.dot(c) + offset) > gate) continue;
            mean += c;
            second += c * c.transpose();
            ++num_inliers;
        }
        if (num_inliers < config.min_ground_points) return result;
        mean /= num_inliers;
        const Eigen::Matrix3d covariance = second / num_inliers - mean * mean.transpose();
        const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(covariance);
        normal = solver.eigenvectors().col(0);
        if (normal.z() < 0) normal = -normal;
        offset = -normal.dot(mean);
    }
    const double tilt = std::acos(std::clamp(normal.z(), -1.0, 1.0));
    if (tilt > config.max_tilt_deg * M_PI / 180.0) return result;

    // Minimal rotation taking the plane normal onto +z (no yaw), then shift the plane to z = 0.
    const Eigen::Matrix3d R = Eigen::Quaterniond::FromTwoVectors(normal, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    result.T_ground_map.linear() = R;
    result.T_ground_map.translation() = Eigen::Vector3d(0.0, 0.0, offset);
    result.num_ground_points = num_inliers;
    result.aligned = true;
    return result;
}

}  // namespace revisit
