#include "odometry/preprocess.hpp"

#include <algorithm>
#include <cmath>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tsl/robin_map.h>

#include "core/se3.hpp"
#include "odometry/voxel_hash_map.hpp"

namespace revisit {

std::vector<Eigen::Vector3d> CropRange(const std::vector<Eigen::Vector3f>& points, double min_range,
                                       double max_range, std::vector<std::size_t>* kept) {
    const double min2 = min_range * min_range;
    const double max2 = max_range * max_range;
    std::vector<Eigen::Vector3d> cropped;
    cropped.reserve(points.size());
    if (kept != nullptr) {
        kept->clear();
        kept->reserve(points.size());
    }
    for (std::size_t i = 0; i < points.size(); ++i) {
        const Eigen::Vector3d p = points[i].cast<double>();
        const double range2 = p.squaredNorm();
        if (range2 < min2 || range2 > max2 || !p.allFinite()) continue;
        cropped.push_back(p);
        if (kept != nullptr) kept->push_back(i);
    }
    return cropped;
}

std::vector<double> SweepTimes(const Scan& scan, bool azimuth_clockwise) {
    std::vector<double> times(scan.points.size());
    if (scan.has_point_times() && scan.point_times.size() == scan.points.size()) {
        const auto [lo, hi] = std::minmax_element(scan.point_times.begin(), scan.point_times.end());
        const double span = static_cast<double>(*hi) - static_cast<double>(*lo);
        for (std::size_t i = 0; i < times.size(); ++i) {
            times[i] = span > 0.0 ? (static_cast<double>(scan.point_times[i]) - *lo) / span : 1.0;
        }
        return times;
    }
    const double sign = azimuth_clockwise ? -1.0 : 1.0;
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, times.size(), 4096), [&](const auto& range) {
        for (std::size_t i = range.begin(); i != range.end(); ++i) {
            const auto& p = scan.points[i];
            const double azimuth = std::atan2(static_cast<double>(p.y()), static_cast<double>(p.x()));
            times[i] = 0.5 * (1.0 + sign * azimuth / M_PI);
        }
    });
    return times;
}

std::vector<Eigen::Vector3d> Deskew(const std::vector<Eigen::Vector3d>& points, const std::vector<double>& sweep_times,
                                    const Eigen::Isometry3d& delta) {
    // exp((s - 1) xi) tabulated at 1024 steps of s and interpolated linearly in between: the
    // interpolation error is O((theta / 1024)^2), below 1e-9 m for any plausible sweep motion,
    // and a point costs a lerp instead of an SE(3) exponential.
    constexpr int kSteps = 1024;
    const Vector6d xi = LogSE3(delta);
    std::vector<Eigen::Matrix<double, 3, 4>> table(kSteps + 1);
    for (int k = 0; k <= kSteps; ++k) table[k] = ExpSE3((static_cast<double>(k) / kSteps - 1.0) * xi).matrix().topRows<3>();
    std::vector<Eigen::Vector3d> deskewed(points.size());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, points.size(), 4096), [&](const auto& range) {
        for (std::size_t i = range.begin(); i != range.end(); ++i) {
            const double u = std::clamp(sweep_times[i], 0.0, 1.0) * kSteps;
            const int k = std::min(static_cast<int>(u), kSteps - 1);
            const double a = u - k;
            const Eigen::Matrix<double, 3, 4> T = (1.0 - a) * table[k] + a * table[k + 1];
            deskewed[i] = T.leftCols<3>() * points[i] + T.col(3);
        }
    });
    return deskewed;
}

bool PreparedScan::PreparedFor(const OdometryConfig& config) const {
    return min_range == config.min_range && max_range == config.max_range && voxel_size == config.VoxelSize() &&
           deskew == config.deskew;
}

PreparedScan PrepareScan(const Scan& scan, const OdometryConfig& config) {
    PreparedScan prepared;
    prepared.min_range = config.min_range;
    prepared.max_range = config.max_range;
    prepared.voxel_size = config.VoxelSize();
    prepared.deskew = config.deskew;
    if (config.deskew) {
        // Deskewing needs the motion predicted from the scan before: the downsampling waits for it.
        std::vector<std::size_t> kept;
        prepared.cropped = CropRange(scan.points, config.min_range, config.max_range, &kept);
        const std::vector<double> all_times = SweepTimes(scan, config.azimuth_clockwise);
        prepared.sweep_times.resize(kept.size());
        for (std::size_t i = 0; i < kept.size(); ++i) prepared.sweep_times[i] = all_times[kept[i]];
        return prepared;
    }
    prepared.cropped = CropRange(scan.points, config.min_range, config.max_range);
    prepared.downsampled = VoxelDownsample(prepared.cropped, 0.5 * prepared.voxel_size);
    prepared.source = VoxelDownsample(prepared.downsampled, 1.5 * prepared.voxel_size);
    return prepared;
}

}  // namespace revisit
