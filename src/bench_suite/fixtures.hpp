#pragma once
/// Data the benchmark cases run on: simulated sequences (sim presets) and, when present, the real data
/// of ../shared/data. Built once per suite and shared by the cases.
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "closures/local_map.hpp"
#include "core/scan.hpp"
#include "odometry/odometry_config.hpp"

namespace revisit {

/// The first `max_scans` scans of a simulator preset (points in the sensor frame, T_world_sensor set).
std::vector<Scan> SimulatedScans(const std::string& preset, std::size_t max_scans, std::uint64_t seed = 1);

/// Up to `max_scans` scans of a dataset from scan number `first` on, read with the ordinary reader
/// (empty when the path is absent).
std::vector<Scan> DatasetScans(const std::filesystem::path& path, std::size_t max_scans, double laser_aperture = 0.0,
                               std::size_t first = 0);

/// One local map (no split) accumulated from `scans` at their T_world_sensor poses (reference poses).
LocalMap AccumulateMap(const std::vector<Scan>& scans, std::size_t first, std::size_t last, int id);

/// Odometry parameters for a sensor family: "64-beam", "livox", "2d".
OdometryConfig OdometryConfigFor(const std::string& sensor);

/// Fixtures cached per suite run, so each sequence is simulated or read once.
class FixtureCache {
  public:
    const std::vector<Scan>& Simulated(const std::string& preset, std::size_t max_scans);
    const std::vector<Scan>& Dataset(const std::filesystem::path& path, std::size_t max_scans,
                                     double laser_aperture = 0.0, std::size_t first = 0);

  private:
    std::map<std::string, std::vector<Scan>> scans_;
};

}  // namespace revisit
