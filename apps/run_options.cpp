#include "run_options.hpp"

#include <filesystem>

#include "core/error.hpp"
#include "settings/auto_settings.hpp"

namespace revisit::app {
namespace fs = std::filesystem;

void AddConfigOptions(CLI::App& cmd, ConfigOptions& options) {
    cmd.add_option("--config", options.configs,
                   "YAML config layered over the defaults; a preset name (kitti, ouster, livox, handheld, indoor2d, "
                   "depth) or a file; repeatable");
    cmd.add_option("--set", options.overrides, "override one parameter, e.g. --set density.resolution=0.2; repeatable");
    cmd.add_option("--threads", options.threads, "worker threads (default: all cores)")->check(CLI::Range(0, 1024));
}

PipelineConfig ResolveConfig(const ConfigOptions& options) {
    std::vector<std::string> files;
    for (const auto& name : options.configs) {
        const bool is_path = name.find('/') != std::string::npos || fs::path(name).extension() == ".yaml" || fs::exists(name);
        const fs::path file = is_path ? fs::path(name) : fs::path(REVISIT_CONFIG_DIR) / (name + ".yaml");
        if (!fs::exists(file)) throw ConfigError("--config " + name + ": no such file or preset (" + file.string() + ")");
        files.push_back(file.string());
    }
    return LoadConfig(files, options.overrides);
}

PipelineConfig ResolveConfigFor(const ConfigOptions& options, const fs::path& dataset, std::ostream& log) {
    PipelineConfig config = ResolveConfig(options);
    const AutoSettings settings = ConfigureFromData(config, dataset);
    PrintAutoSettings(log, settings, dataset);
    config.derived = settings.Describe();
    for (const auto& warning : settings.warnings) config.derived.push_back("warning: " + warning);
    return config;
}

std::unique_ptr<tbb::global_control> LimitThreads(int threads) {
    if (threads <= 0) return nullptr;
    return std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, threads);
}

}  // namespace revisit::app
