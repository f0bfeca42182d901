#pragma once
/// What `revisit run` and `revisit demo` do after parsing: the pipeline, then evaluation and the
/// report (skipped after Ctrl-C: `revisit eval` / `revisit report` can finish them later), then
/// the summary table.
#include <ostream>

#include "pipeline/pipeline.hpp"

namespace revisit {

/// Progress and notes go to `log`, the summary and the paths to `out`. Returns the run's state.
RunState RunAndReport(const RunOptions& options, const PipelineConfig& config, std::ostream& log, std::ostream& out);

}  // namespace revisit
