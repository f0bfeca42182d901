#pragma once
/// Named simulator configurations (`revisit simulate --preset NAME`).
#include <filesystem>
#include <string>
#include <vector>

#include "sim/simulate.hpp"

namespace revisit {

/// The configuration of a preset; throws ConfigError naming the known presets for an unknown name.
/// "demo" (= "city-64"): a ~3 km city drive with an HDL-64E-like sensor and >= 5 revisits, one opposite.
SimConfig SimPreset(const std::string& name);

/// A city or highway preset's drive stretched to `length` [m] (long drives: hours of data, the paper's
/// 23 km highway). The world grows with the route, so that most of it explores new ground and the
/// revisits come after long stretches; the planned revisits grow with it. Throws ConfigError for the
/// other worlds (indoor floors, a given trajectory) and for lengths outside [100 m, 500 km].
SimConfig WithRouteLength(SimConfig config, double length);

/// A preset's sensor and city densities in a street world built along the KITTI or TUM poses of
/// `trajectory_file` (`revisit simulate --trajectory`): the route is that trajectory.
SimConfig AlongTrajectory(SimConfig config, const std::filesystem::path& trajectory_file);

/// Every preset name, in documentation order.
std::vector<std::string> SimPresetNames();

}  // namespace revisit
