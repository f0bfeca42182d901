#include "io/rawlog_scan.hpp"

#include <mrpt/maps/CPointsMapXYZI.h>
#include <mrpt/maps/CSimplePointsMap.h>
#include <mrpt/obs/CObservation2DRangeScan.h>
#include <mrpt/obs/CObservation3DRangeScan.h>
#include <mrpt/obs/CObservationPointCloud.h>
#include <mrpt/obs/CObservationRotatingScan.h>
#include <mrpt/obs/CObservationVelodyneScan.h>
#include <mrpt/system/datetime.h>

#include <cmath>
#include <cstdint>
#include <cstring>

#include "io/rotating_scan.hpp"

namespace revisit {

Eigen::Isometry3d ToIsometry(const mrpt::poses::CPose3D& pose) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.matrix() = pose.getHomogeneousMatrixVal<mrpt::math::CMatrixDouble44>().asEigen();
    return T;
}

mrpt::poses::CPose3D ToCPose3D(const Eigen::Isometry3d& T) {
    return mrpt::poses::CPose3D(mrpt::math::CMatrixDouble44(T.matrix()));
}

namespace {

/// Builds a scan from parallel coordinate arrays, dropping non-finite points.
template <typename Get>
Scan CollectPoints(std::size_t n, bool with_intensity, bool with_time, Get get, ReadStats& stats) {
    Scan scan;
    scan.points.reserve(n);
    for (std::size_t i = 0; i < n; ++i) {
        float x, y, z, intensity = 0.f, time = 0.f;
        get(i, x, y, z, intensity, time);
        if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z)) {
            stats.non_finite_points++;
            continue;
        }
        scan.points.emplace_back(x, y, z);
        if (with_intensity) scan.intensities.push_back(intensity);
        if (with_time) scan.point_times.push_back(time);
    }
    return scan;
}

Scan FromPointsMap(const mrpt::maps::CPointsMap& map, ReadStats& stats) {
    const auto& xs = map.getPointsBufferRef_x();
    const auto& ys = map.getPointsBufferRef_y();
    const auto& zs = map.getPointsBufferRef_z();
    const auto* xyzi = dynamic_cast<const mrpt::maps::CPointsMapXYZI*>(&map);
    return CollectPoints(
        map.size(), xyzi != nullptr, false,
        [&](std::size_t i, float& x, float& y, float& z, float& intensity, float&) {
            x = xs[i], y = ys[i], z = zs[i];
            if (xyzi) intensity = xyzi->getPointIntensity_fast(i);
        },
        stats);
}

std::optional<Scan> PointsOf(const mrpt::obs::CObservation& obs, ReadStats& stats, const ReaderOptions& options) {
    using namespace mrpt::obs;
    if (const auto* pc = dynamic_cast<const CObservationPointCloud*>(&obs)) {
        if (!pc->pointcloud) return Scan{};
        return FromPointsMap(*pc->pointcloud, stats);
    }
    if (const auto* velodyne = dynamic_cast<const CObservationVelodyneScan*>(&obs)) {
        CObservationVelodyneScan copy(*velodyne);  // generatePointCloud() fills a member
        CObservationVelodyneScan::TGeneratePointCloudParameters params;
        params.generatePerPointTimestamp = true;
        copy.generatePointCloud(params);
        const auto& pc = copy.point_cloud;
        const bool with_time = pc.timestamp.size() == pc.x.size();
        return CollectPoints(
            pc.x.size(), true, with_time,
            [&](std::size_t i, float& x, float& y, float& z, float& intensity, float& time) {
                x = pc.x[i], y = pc.y[i], z = pc.z[i], intensity = pc.intensity[i] / 255.f;
                if (with_time) time = static_cast<float>(mrpt::system::timeDifference(copy.timestamp, pc.timestamp[i]));
            },
            stats);
    }
    if (const auto* depth = dynamic_cast<const CObservation3DRangeScan*>(&obs)) {
        if (!depth->hasRangeImage) return Scan{};
        CObservation3DRangeScan copy(*depth);  // unprojectInto() may load external images into the object
        mrpt::maps::CSimplePointsMap map;
        copy.unprojectInto(map);
        return FromPointsMap(map, stats);
    }
    if (const auto* laser = dynamic_cast<const CObservation2DRangeScan*>(&obs)) {
        Scan scan;
        const std::size_t n = laser->getScanSize();
        const double aperture = options.laser_aperture > 0.0 ? options.laser_aperture : laser->aperture;
        const double step = n > 1 ? aperture / static_cast<double>(n - 1) : 0.0;
        PlanarBeams beams;
        beams.ranges.assign(n, 0.f);
        beams.aperture = aperture;
        beams.stated_aperture = laser->aperture;
        // MRPT reads the flag as a raw byte: a damaged file can hold a value no bool has (found by fuzz_rawlog).
        std::uint8_t right_to_left_byte = 0;
        std::memcpy(&right_to_left_byte, &laser->rightToLeft, 1);
        const bool right_to_left = right_to_left_byte != 0;
        for (std::size_t i = 0; i < n; ++i) {
            if (!laser->getScanRangeValidity(i)) continue;
            const float range = laser->getScanRange(i);
            if (std::isfinite(range)) beams.ranges[right_to_left ? i : n - 1 - i] = range;
            // As CObservation2DRangeScan::getScanAngle, with the aperture possibly overridden.
            const double from_right = -aperture / 2.0 + step * static_cast<double>(i);
            const float angle = static_cast<float>(right_to_left ? from_right : -from_right);
            const Eigen::Vector3f point(range * std::cos(angle), range * std::sin(angle), 0.f);
            if (!point.allFinite()) {  // a NaN range, or a damaged aperture
                stats.non_finite_points++;
                continue;
            }
            scan.points.push_back(point);
        }
        scan.planar_beams = std::move(beams);
        return scan;
    }
    if (const auto* rotating = dynamic_cast<const CObservationRotatingScan*>(&obs)) {
        return RotatingScanPoints(*rotating, stats);
    }
    return std::nullopt;
}

}  // namespace

std::optional<Scan> ScanFromObservation(const mrpt::obs::CObservation& obs, ReadStats& stats, const ReaderOptions& options) {
    auto scan = PointsOf(obs, stats, options);
    if (!scan) return std::nullopt;
    mrpt::poses::CPose3D sensor_pose;
    obs.getSensorPose(sensor_pose);
    const Eigen::Isometry3d T_vehicle_sensor = ToIsometry(sensor_pose);
    if (scan->planar_beams) scan->planar_beams->T_vehicle_sensor = T_vehicle_sensor;
    if (!T_vehicle_sensor.isApprox(Eigen::Isometry3d::Identity(), 0.0)) {  // identity skipped: converted points stay bit-exact
        const Eigen::Isometry3f T = T_vehicle_sensor.cast<float>();
        for (auto& p : scan->points) p = T * p;
    }
    scan->timestamp = obs.timestamp == INVALID_TIMESTAMP ? 0.0 : mrpt::Clock::toDouble(obs.timestamp);
    scan->sensor_label = obs.sensorLabel;
    return scan;
}

}  // namespace revisit
