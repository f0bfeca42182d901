#pragma once
/// What `revisit run` and `revisit demo` do after parsing: the pipeline, then evaluation and the
/// report (skipped after Ctrl-C: `revisit eval` / `revisit report` can finish them later), then
/// the summary table.
#include <ostream>

#include "pipeline/pipeline.hpp"

namespace revisit {

/// Progress and notes go to `log`, the summary and the paths to `out`. Returns the run's state as the
/// summary needs it: before the evaluation (which reads the run folder's own copy) the chain's state
/// lets go of the closures' matches, the comparisons and every pose but the odometry's; the run folder
/// has them all (ReadRunState).
RunState RunAndReport(const RunOptions& options, const PipelineConfig& config, std::ostream& log, std::ostream& out);

}  // namespace revisit
