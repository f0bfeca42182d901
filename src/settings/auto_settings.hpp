#pragma once
/// The one place that turns what the data shows (a DataProfile, a 2D laser's measured aperture)
/// into settings. Each choice says why; keys a config file or --set gave (PipelineConfig::
/// explicit_keys) are never changed, but a given value the data contradicts gets a warning.
#include <filesystem>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "config/config.hpp"
#include "settings/data_profile.hpp"
#include "settings/laser_aperture.hpp"

namespace revisit {

struct SettingChoice {
    std::string key;     ///< e.g. "odometry.voxel_size"
    double value = 0.0;  ///< chosen value (booleans as 0/1)
    std::string text;    ///< a named choice (e.g. density.scaling "percentile"); empty: `value`
    std::string reason;  ///< what in the data led to it
    bool applied = false;  ///< false: the key was given explicitly and kept
};

struct AutoSettings {
    DataProfile profile;
    std::optional<ApertureEstimate> aperture;  ///< 2D lasers with an odometry prior
    std::vector<SettingChoice> choices;
    std::vector<std::string> warnings;  ///< explicit values the data contradicts, corrected apertures

    /// What was chosen and why, one line each (the run log, config.yaml's header).
    std::vector<std::string> Describe() const;
};

/// The odometry's crop radius for a scene whose points lie within `range_p99` [m] (99%): 1.5 x that,
/// in 10 m steps, within [30, 300] m. Used at the start and as the scene unfolds (SceneScaleWatch).
double MaxRangeFor(double range_p99);

/// The settings that follow from `profile` (and a measured aperture), before any are applied.
/// `given_map_length`: a local-map length the user gave [m]; the settings that scale with it (the
/// skip of recent maps, the carry-over radius, the small-scale detector) follow it instead.
std::vector<SettingChoice> ChooseSettings(const DataProfile& profile, const std::optional<ApertureEstimate>& aperture,
                                          std::optional<double> given_map_length = std::nullopt);

/// Applies the choices to every key `config` does not give explicitly; warns where an explicit value
/// is far (3x) from what the data suggests. Deterministic: the same profile gives the same settings.
AutoSettings ApplyAutoSettings(PipelineConfig& config, const DataProfile& profile,
                               const std::optional<ApertureEstimate>& aperture = std::nullopt);

/// Reads the first scans of `dataset` with `config`'s reader options (a reader of its own; the run
/// opens the dataset afresh), profiles them, checks a 2D laser's aperture, and applies the result.
/// Does nothing (an empty result) when `config.input.auto_settings` is false.
AutoSettings ConfigureFromData(PipelineConfig& config, const std::filesystem::path& dataset);

/// Prints what was chosen and the warnings, prefixed "revisit: ".
void PrintAutoSettings(std::ostream& log, const AutoSettings& settings, const std::filesystem::path& dataset);

}  // namespace revisit
