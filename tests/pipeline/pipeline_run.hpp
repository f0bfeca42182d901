#pragma once
/// The whole pipeline over a dataset with a given config, quietly, into a run folder that is removed
/// afterwards: for tests that look only at the run's state.
#include <filesystem>
#include <sstream>

#include "pipeline/pipeline.hpp"
#include "test_data.hpp"

namespace revisit::test {

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
