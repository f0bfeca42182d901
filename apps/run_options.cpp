#include "run_options.hpp"

#include <filesystem>

#include "settings/resolve_config.hpp"

namespace revisit::app {
namespace fs = std::filesystem;

void AddConfigOptions(CLI::App& cmd, ConfigOptions& options) {
    cmd.add_option("--config", options.configs,
                   "YAML config layered over the defaults; a preset name (kitti, ouster, livox, handheld, indoor2d, "
                   "depth) or a file; repeatable");
    cmd.add_option("--set", options.overrides, "override one parameter, e.g. --set density.resolution=0.2; repeatable");
    cmd.add_option("--threads", options.threads, "worker threads (default: all cores)")->check(CLI::Range(0, 1024));
}

PipelineConfig ResolveConfig(const ConfigOptions& options) { return revisit::ResolveConfig(options.configs, options.overrides); }

PipelineConfig ResolveConfigFor(const ConfigOptions& options, const fs::path& dataset, std::ostream& log) {
    return revisit::ResolveConfigFor(options.configs, options.overrides, dataset, log);
}

std::unique_ptr<tbb::global_control> LimitThreads(int threads) {
    if (threads <= 0) return nullptr;
    return std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, threads);
}

}  // namespace revisit::app
