#pragma once
/// The unit of data every stage consumes: one sweep of a range sensor.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace revisit {

/// A 2D laser's beams as the file states them, kept so the stated geometry can be checked against
/// the data (src/settings/laser_aperture.hpp). Points are built with `aperture`.
struct PlanarBeams {
    std::vector<float> ranges;     ///< [m] per beam in order of increasing angle; 0 = no return
    double aperture = 0.0;         ///< [rad] field of view used to place the beams
    double stated_aperture = 0.0;  ///< [rad] what the file says
    Eigen::Isometry3d T_vehicle_sensor = Eigen::Isometry3d::Identity();  ///< where the laser sits
};

struct Scan {
    std::size_t index = 0;                 ///< position in the sequence, from 0
    double timestamp = 0.0;                ///< [s] sensor clock (KITTI: times.txt)
    std::int64_t stamp_ns = 0;             ///< [ns] the same stamp exactly, when the format has one (ROS bags), else 0
    std::string sensor_label;              ///< e.g. "VELODYNE", "LASER"; file format name when unknown
    std::vector<Eigen::Vector3f> points;   ///< [m] in the sensor frame, finite only
    std::vector<float> intensities;        ///< one per point, or empty when the format has none
    std::vector<float> point_times;        ///< [s] relative to `timestamp`, one per point, or empty
    std::optional<Eigen::Isometry3d> T_world_sensor;  ///< reference (ground-truth) pose, if known
    std::optional<Eigen::Isometry3d> T_odom_sensor;   ///< odometry prior (e.g. wheel odometry), if known
    std::optional<PlanarBeams> planar_beams;          ///< 2D lasers: the beams behind `points`

    bool has_intensities() const { return !intensities.empty(); }
    bool has_point_times() const { return !point_times.empty(); }
};

}  // namespace revisit
