#pragma once
/// The configuration a run uses, resolved the same way by every front end (the CLI's --config/--set,
/// the Python module's load_config): built-in defaults, then each file or preset, then each override,
/// then every setting none of them gave derived from the dataset's first scans.
#include <filesystem>
#include <ostream>
#include <string>
#include <vector>

#include "config/config.hpp"

namespace revisit {

/// The folder the preset names (`kitti`, `indoor2d`, ...) are read from: the source tree's configs/
/// this library was built from.
std::filesystem::path PresetDirectory();

/// A preset name (no slash, no .yaml, no such file) -> PresetDirectory()/NAME.yaml; a path stays as it
/// is. Throws ConfigError naming the entry when the file does not exist.
std::filesystem::path ResolveConfigFile(const std::string& name_or_path);

/// configs/default.yaml semantics (the built-in defaults), then each file or preset, then each key=value.
PipelineConfig ResolveConfig(const std::vector<std::string>& configs, const std::vector<std::string>& overrides);

/// Every setting `config` was not given explicitly, derived from the dataset's first scans
/// (auto_settings.hpp), printed with the reasons on `log` and kept in `config.derived` for config.yaml.
void DeriveSettingsFromData(PipelineConfig& config, const std::filesystem::path& dataset, std::ostream& log);

/// ResolveConfig, then DeriveSettingsFromData.
PipelineConfig ResolveConfigFor(const std::vector<std::string>& configs, const std::vector<std::string>& overrides,
                                const std::filesystem::path& dataset, std::ostream& log);

}  // namespace revisit
