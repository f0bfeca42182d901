#include "settings/resolve_config.hpp"

#include "core/error.hpp"
#include "settings/auto_settings.hpp"

namespace revisit {
namespace fs = std::filesystem;

fs::path PresetDirectory() { return fs::path(REVISIT_CONFIG_DIR_DEFAULT); }

fs::path ResolveConfigFile(const std::string& name) {
    const bool is_path = name.find('/') != std::string::npos || fs::path(name).extension() == ".yaml" || fs::exists(name);
    const fs::path file = is_path ? fs::path(name) : PresetDirectory() / (name + ".yaml");
    if (!fs::exists(file)) throw ConfigError("--config " + name + ": no such file or preset (" + file.string() + ")");
    return file;
}

PipelineConfig ResolveConfig(const std::vector<std::string>& configs, const std::vector<std::string>& overrides) {
    std::vector<std::string> files;
    for (const auto& name : configs) files.push_back(ResolveConfigFile(name).string());
    return LoadConfig(files, overrides);
}

void DeriveSettingsFromData(PipelineConfig& config, const fs::path& dataset, std::ostream& log) {
    const AutoSettings settings = ConfigureFromData(config, dataset);
    PrintAutoSettings(log, settings, dataset);
    config.derived = settings.Describe();
    for (const auto& warning : settings.warnings) config.derived.push_back("warning: " + warning);
}

PipelineConfig ResolveConfigFor(const std::vector<std::string>& configs, const std::vector<std::string>& overrides,
                                const fs::path& dataset, std::ostream& log) {
    PipelineConfig config = ResolveConfig(configs, overrides);
    DeriveSettingsFromData(config, dataset, log);
    return config;
}

}  // namespace revisit
