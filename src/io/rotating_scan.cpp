#include "io/rotating_scan.hpp"

#include <cmath>

namespace revisit {

std::optional<std::vector<double>> RotatingScanElevations(const std::string& lidar_model, int row_count) {
    constexpr double kDeg = M_PI / 180.0;
    if (row_count == 1) return std::vector<double>{0.0};
    if (row_count == 16 && (lidar_model == "VLP-16" || lidar_model == "VLP16")) {
        // VLP-16 datasheet, laser ids 0..15 in firing order: -15, 1, -13, 3, ..., -1, 15 degrees.
        std::vector<double> elevations(16);
        for (int id = 0; id < 16; ++id) elevations[id] = (id % 2 == 0 ? -15 + id : id) * kDeg;
        return elevations;
    }
    return std::nullopt;
}

std::optional<Scan> RotatingScanPoints(const mrpt::obs::CObservationRotatingScan& obs, ReadStats& stats) {
    const auto elevations = RotatingScanElevations(obs.lidarModel, obs.rowCount);
    if (!elevations) return std::nullopt;
    const int rows = obs.rowCount, cols = obs.columnCount;
    if (obs.rangeImage.rows() != rows || obs.rangeImage.cols() != cols) return Scan{};
    const bool with_intensity = obs.intensityImage.rows() == rows && obs.intensityImage.cols() == cols;
    // MRPT documents startAzimuth and startAzimuth + azimuthSpan as the azimuths of the first and last
    // columns. MRPT 2.5.8's fromVelodyne() fills only the first ~1800 of its 28800 columns with a full
    // sweep, so the "last column" is taken as the last one with a return. It also keeps the
    // Velodyne's clockwise azimuth although the header documents counter-clockwise. Both facts are
    // checked against the same sweep decoded from raw packets (test_velodyne_VLP16.rawlog vs
    // rot_scan_velodyne.rawlog). Planar scans converted from CObservation2DRangeScan are counter-clockwise.
    int last_column = 0;
    for (int c = 0; c < cols; ++c) {
        for (int r = 0; r < rows; ++r) {
            if (obs.rangeImage(r, c) != 0) last_column = c;
        }
    }
    const double y_sign = obs.lidarModel.rfind("2D_SCAN", 0) == 0 ? 1.0 : -1.0;
    const double step = last_column > 0 ? obs.azimuthSpan / last_column : 0.0;
    const double time_step = last_column > 0 ? obs.sweepDuration / last_column : 0.0;
    Scan scan;
    for (int c = 0; c < cols; ++c) {
        const double azimuth = obs.startAzimuth + step * c;
        for (int r = 0; r < rows; ++r) {
            const auto raw = obs.rangeImage(r, c);
            if (raw == 0) continue;  // no return
            const double range = raw * obs.rangeResolution;
            const double el = (*elevations)[r];
            const Eigen::Vector3f p(static_cast<float>(range * std::cos(el) * std::cos(azimuth)),
                                    static_cast<float>(y_sign * range * std::cos(el) * std::sin(azimuth)),
                                    static_cast<float>(range * std::sin(el)));
            if (!p.allFinite()) {
                stats.non_finite_points++;
                continue;
            }
            scan.points.push_back(p);
            if (with_intensity) scan.intensities.push_back(obs.intensityImage(r, c) / 255.f);
            scan.point_times.push_back(static_cast<float>(time_step * c));
        }
    }
    return scan;
}

}  // namespace revisit
