#pragma once
/// The whole pipeline over a dataset with a given config, quietly, into a run folder that is removed
/// afterwards: for tests that look only at the run's state.
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "config/config.hpp"
#include "pipeline/pipeline.hpp"
#include "settings/auto_settings.hpp"
#include "test_data.hpp"

namespace revisit::test {

/// What `revisit run DATASET` configures (the defaults, then the settings from the data; explicit values
/// win), with `overrides` as --set, and no report, ScanContext baseline or elevation ablation.
inline PipelineConfig DefaultsFor(const std::filesystem::path& dataset, const std::vector<std::string>& overrides = {}) {
    std::vector<std::string> sets = {"output.write_report=false", "output.scan_context=false", "output.elevation_ablation=false"};
    sets.insert(sets.end(), overrides.begin(), overrides.end());
    PipelineConfig config = LoadConfig({}, sets);
    ConfigureFromData(config, dataset);
    return config;
}

/// Options of a quiet run of `dataset` into `out`.
inline RunOptions QuietRunOptions(const std::filesystem::path& dataset, const std::filesystem::path& out) {
    RunOptions options;
    options.dataset = dataset;
    options.out = out;
    options.quiet = true;
    return options;
}

inline RunState RunQuietly(const std::filesystem::path& dataset, const PipelineConfig& config) {
    TempDir out;
    RunOptions options;
    options.dataset = dataset;
    options.out = out / "run";
    options.quiet = true;
    std::ostringstream log;
    return RunPipeline(options, config, log);
}

}  // namespace revisit::test
