#pragma once
/// The simulator as a dataset: `sim:PRESET` streams the scans `revisit simulate --preset PRESET` would
/// write, ray-cast as they are read, so a demo or a long drive needs no disk for its scans.
#include <memory>
#include <string>

#include "io/reader.hpp"
#include "sim/simulate.hpp"

namespace revisit {

/// Scans of `config` in order, as its KITTI folder would hold them: points and intensities as float32,
/// the reference pose, the time stamp; no per-point times and no odometry prior (the folder has neither).
/// `name` is what Info().path says (e.g. "sim:demo").
std::unique_ptr<Reader> OpenSimulation(const SimConfig& config, const std::string& name);

/// "sim:PRESET" or "sim:PRESET,length=METRES" (WithRouteLength) -> the configuration; throws DatasetError
/// naming the spec for an unknown preset or option.
SimConfig SimConfigFromSpec(const std::string& spec);

/// Lets OpenDataset read "sim:PRESET" (io/reader.hpp: RegisterDatasetScheme). Call once, before any
/// dataset is opened; the command's main does.
void RegisterSimulatorDatasets();

}  // namespace revisit
