#pragma once
/// closures.json: every accepted closure for SLAM systems to consume: both maps' origin scans (index and
/// stamp), the relative pose and its covariance as the pose graph weighed it.
#include <filesystem>
#include <ostream>

#include "config/config.hpp"
#include "runfolder/run_state.hpp"

namespace revisit {

void WriteClosuresJson(std::ostream& out, const RunState& state, const PipelineConfig& config);

/// The information matrices closures.json recorded, put back into `state`'s closures (matched by their
/// closures.csv row), so a finished run's export uses what its graph used.
void ReadClosureInformation(const std::filesystem::path& closures_json, RunState& state);

}  // namespace revisit
