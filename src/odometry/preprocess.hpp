#pragma once
/// Per-frame preprocessing of the odometry (METHOD.md section 1): range crop, deskew,
/// voxel downsampling.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <vector>

#include "core/scan.hpp"
#include "core/voxel.hpp"  // VoxelDownsample
#include "odometry/odometry_config.hpp"

namespace revisit {

/// Points with range in [min_range, max_range] [m], in double precision, input order kept.
/// `kept`, when given, receives the input index of every returned point.
std::vector<Eigen::Vector3d> CropRange(const std::vector<Eigen::Vector3f>& points, double min_range,
                                       double max_range, std::vector<std::size_t>* kept = nullptr);

/// Normalized acquisition time s in [0, 1] of every point of the scan: from Scan::point_times
/// when present (min -> 0, max -> 1), otherwise from the azimuth of a spinning sensor
/// (clockwise: s = 0.5 (1 - atan2(y, x) / pi), the KITTI convention of KISS-ICP).
std::vector<double> SweepTimes(const Scan& scan, bool azimuth_clockwise);

/// Motion compensation with a constant-velocity model: a point taken at sweep time s is moved
/// into the sensor frame at the end of the sweep, p' = exp((s - 1) log(delta)) p, where `delta`
/// is the sensor motion over one sweep (T_prev^-1 T_curr). METHOD.md section 1.
std::vector<Eigen::Vector3d> Deskew(const std::vector<Eigen::Vector3d>& points, const std::vector<double>& sweep_times,
                                    const Eigen::Isometry3d& delta);

/// What of a scan's odometry does not depend on the scans before it (METHOD.md section 1): the range
/// crop and, without deskewing, both downsamplings. PrepareScan can thus run ahead, on another thread,
/// while the scan before registers (issue 19: the preprocessing is half of a KITTI scan's odometry and
/// serial, so at two threads it set the pace).
struct PreparedScan {
    double min_range = 0.0;  ///< [m] the settings it was prepared with (LidarOdometry redoes it if they changed)
    double max_range = 0.0;  ///< [m]
    double voxel_size = 0.0; ///< [m] the map voxel v
    bool deskew = false;
    std::vector<Eigen::Vector3d> cropped;      ///< in range, sensor frame, input order (not yet deskewed)
    std::vector<double> sweep_times;           ///< deskew only: sweep time of each cropped point
    std::vector<Eigen::Vector3d> downsampled;  ///< without deskew: first point per 0.5 v voxel
    std::vector<Eigen::Vector3d> source;       ///< without deskew: first point per 1.5 v voxel of `downsampled`

    /// Prepared with `config`'s crop, voxel and deskew settings.
    bool PreparedFor(const OdometryConfig& config) const;
};

/// Prepares a scan for LidarOdometry::RegisterPrepared with `config`'s settings.
PreparedScan PrepareScan(const Scan& scan, const OdometryConfig& config);

}  // namespace revisit
