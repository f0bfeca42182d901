#pragma once
/// Options shared by the commands that run stages: config layering and threads.
#include <CLI/CLI.hpp>
#include <oneapi/tbb/global_control.h>

#include <filesystem>
#include <memory>
#include <ostream>
#include <string>
#include <vector>

#include "config/config.hpp"

namespace revisit::app {

struct ConfigOptions {
    std::vector<std::string> configs;    ///< files or preset names, applied in order
    std::vector<std::string> overrides;  ///< key=value
    int threads = 0;                     ///< 0: all cores
};

void AddConfigOptions(CLI::App& cmd, ConfigOptions& options);

/// configs/default.yaml semantics (the built-in defaults), then each --config, then each --set.
/// A name without a slash or .yaml is a preset from the configs/ folder.
PipelineConfig ResolveConfig(const ConfigOptions& options);

/// ResolveConfig, then every setting no --config/--set gave derived from the dataset's first scans
/// (src/settings/auto_settings.hpp), printed with the reasons on `log` and kept for config.yaml.
PipelineConfig ResolveConfigFor(const ConfigOptions& options, const std::filesystem::path& dataset, std::ostream& log);

/// Limits TBB (and so Ceres) to `threads` workers for the lifetime of the returned object.
std::unique_ptr<tbb::global_control> LimitThreads(int threads);

}  // namespace revisit::app
