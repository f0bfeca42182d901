#pragma once
/// Per-frame preprocessing of the odometry (METHOD.md section 1): range crop, deskew,
/// voxel downsampling.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <vector>

#include "core/scan.hpp"

#include "core/voxel.hpp"  // VoxelDownsample

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


}  // namespace revisit
