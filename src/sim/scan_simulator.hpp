#pragma once
/// One simulated sweep: rays of a sensor cast into the world from the sensor's pose, with
/// range noise, dropouts, intensities and (optionally) motion distortion.
#include <cstdint>
#include <vector>

#include "core/scan.hpp"
#include "sim/ray_caster.hpp"
#include "sim/sensor.hpp"

namespace revisit {

struct SweepInput {
    std::size_t index = 0;                                        ///< scan index in the sequence
    double timestamp = 0.0;                                       ///< [s] end of the sweep
    Eigen::Isometry3d T_world_sensor = Eigen::Isometry3d::Identity();        ///< at the end of the sweep
    Eigen::Isometry3d T_world_sensor_start = Eigen::Isometry3d::Identity();  ///< at its start (motion distortion)
    std::vector<OrientedBox> dynamic_boxes;                       ///< moving cars at this time
};

/// Simulates one sweep. Each point is in the sensor frame at its own firing time, as a real sensor
/// reports it; with motion distortion on, the sensor moves during the sweep (constant velocity from
/// T_world_sensor_start to T_world_sensor) and point_times [s] are relative to `timestamp` (in
/// [-1/rate, 0]), so that T_world_sensor(timestamp + t) * p puts a point where it was measured. Every random draw
/// is a hash of (seed, index, ray), so the result does not depend on the number of threads.
Scan SimulateScan(const RayCaster& caster, const SensorConfig& sensor, const std::vector<SensorRay>& rays,
                  const SweepInput& sweep, std::uint64_t seed);

}  // namespace revisit
