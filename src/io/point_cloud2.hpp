#pragma once
/// sensor_msgs/PointCloud2 and LaserScan to points, for ROS 1 and ROS 2 alike.
#include "core/scan.hpp"
#include "io/cloud_files.hpp"
#include "io/ros_messages.hpp"

namespace revisit {

/// x, y, z (float32 or float64, required), intensity (first of intensity/i/reflectance, any numeric
/// type) and a per-point time (first of t/time/timestamp/offset_time) from any field layout:
/// organized or not, either byte order, padded points and rows. Non-finite points are dropped and
/// counted. Times become [s] relative to the message stamp:
/// - float fields are seconds; integer fields nanoseconds, except when their span over the cloud is
///   between 1e3 and 1e6 (1 ms..1 s as microseconds, under 1 ms as nanoseconds): microseconds;
/// - values above 1e8 s once scaled are absolute (epoch) times and have the stamp subtracted.
/// Throws WireError when the layout does not fit the data (fields past point_step, rows past the data).
CloudData PointsFromCloud2(const PointCloud2Msg& msg);

/// A 2D scan: points in the laser's plane and the beams behind them (core/scan.hpp PlanarBeams).
/// Ranges outside [range_min, range_max] or non-finite are no returns. `aperture` > 0 replaces the
/// message's angular span [rad], centred on the message's middle beam.
Scan ScanFromLaserScan(const LaserScanMsg& msg, double aperture, std::size_t& non_finite);

}  // namespace revisit
