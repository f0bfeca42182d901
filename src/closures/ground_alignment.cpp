#include "closures/ground_alignment.hpp"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

namespace revisit {
namespace {

/// Cells of a dense grid over the bounding box at most, beyond which the cells are sorted instead:
/// a few far points (3e4 m, 1e5 m) would otherwise make a grid of gigabytes. The memory is then
/// bounded by the number of points whatever their coordinates; both ways give the same candidates in
/// the same (row-major) order.
constexpr double kMaxDenseCells = 4.0 * 1024 * 1024;

std::vector<Eigen::Vector3d> LowestPerCell(const std::vector<Eigen::Vector3f>& points, double cell_size) {
    std::vector<std::size_t> finite;  // a point with an infinite or NaN coordinate has no cell
    finite.reserve(points.size());
    for (std::size_t i = 0; i < points.size(); ++i) {
        if (points[i].allFinite()) finite.push_back(i);
    }
    if (finite.empty()) return {};
    Eigen::Vector2f lo = points[finite.front()].head<2>(), hi = lo;
    for (const auto i : finite) {
        lo = lo.cwiseMin(points[i].head<2>());
        hi = hi.cwiseMax(points[i].head<2>());
    }
    // Cell coordinates in float as the grid always had them (same cells, same candidates); held in
    // double, where any float value, even an overflow to infinity, compares and multiplies safely.
    const float inv = float(1.0 / cell_size);
    const double cols = std::floor(double((hi.x() - lo.x()) * inv)) + 1.0, rows = std::floor(double((hi.y() - lo.y()) * inv)) + 1.0;
    const auto cell_of = [&](std::size_t i) {
        return std::pair<double, double>(std::floor(double((points[i].y() - lo.y()) * inv)),
                                         std::floor(double((points[i].x() - lo.x()) * inv)));
    };
    constexpr std::int32_t kEmpty = -1;
    std::vector<std::int32_t> lowest;  // per occupied cell in row-major order: the index of its lowest point
    if (rows * cols <= std::max(kMaxDenseCells, 4.0 * static_cast<double>(finite.size()))) {
        const auto num_cols = static_cast<std::size_t>(cols);
        std::vector<std::int32_t> grid(static_cast<std::size_t>(rows) * num_cols, kEmpty);
        for (const auto i : finite) {
            const auto [row, col] = cell_of(i);
            auto& cell = grid[static_cast<std::size_t>(row) * num_cols + static_cast<std::size_t>(col)];
            if (cell == kEmpty || points[i].z() < points[std::size_t(cell)].z()) cell = std::int32_t(i);
        }
        for (const auto index : grid) {
            if (index != kEmpty) lowest.push_back(index);
        }
    } else {
        std::vector<std::pair<std::pair<double, double>, std::int32_t>> cells;
        cells.reserve(finite.size());
        for (const auto i : finite) cells.emplace_back(cell_of(i), std::int32_t(i));
        // Sorted by cell, then by index: the first point of a cell wins ties, as in the dense grid.
        std::sort(cells.begin(), cells.end());
        for (std::size_t k = 0; k < cells.size(); ++k) {
            if (k == 0 || cells[k].first != cells[k - 1].first) {
                lowest.push_back(cells[k].second);
            } else if (points[std::size_t(cells[k].second)].z() < points[std::size_t(lowest.back())].z()) {
                lowest.back() = cells[k].second;
            }
        }
    }
    std::vector<Eigen::Vector3d> result;
    result.reserve(lowest.size());
    for (const auto index : lowest) result.push_back(points[std::size_t(index)].cast<double>());
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
