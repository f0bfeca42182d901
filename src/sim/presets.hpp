#pragma once
/// Named simulator configurations (`revisit simulate --preset NAME`).
#include <string>
#include <vector>

#include "sim/simulate.hpp"

namespace revisit {

/// The configuration of a preset; throws ConfigError naming the known presets for an unknown name.
/// "demo" (= "city-64"): a ~3 km city drive with an HDL-64E-like sensor and >= 5 revisits, one opposite.
SimConfig SimPreset(const std::string& name);

/// Every preset name, in documentation order.
std::vector<std::string> SimPresetNames();

}  // namespace revisit
