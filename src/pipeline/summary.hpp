#pragma once
/// The table `revisit run` prints at the end: counts, time per stage, and metrics when evaluated.
#include <optional>
#include <ostream>
#include <string>

#include "pipeline/evaluate.hpp"
#include "runfolder/run_state.hpp"

namespace revisit {

/// Time spent after the chain, shown beside it (absent: that step did not run).
struct PostRunSeconds {
    std::optional<double> evaluation;  ///< [s]
    std::optional<double> report;      ///< [s]
    /// [s] the process's CPU time (ProcessCpuSeconds) up to the chain's end, and spent by each step after it.
    std::optional<double> chain_cpu, evaluation_cpu, report_cpu;
};

void PrintRunSummary(std::ostream& out, const RunState& state, const std::optional<RunEvaluation>& evaluation,
                     const PostRunSeconds& after_chain = {});

/// The run was built on the dataset's own poses (`--poses dataset`), which are also its reference: APE "before"
/// is zero by construction and APE "after" is how far the closures moved the input.
inline bool ReferenceIsInput(const RunState& state) { return state.poses_source == "dataset"; }

/// "1.00 m -> 0.20 m (80% lower)". A change under 1 cm (the printed resolution) or 0.5% is "unchanged"; from
/// under 1 cm a percentage means nothing, so the change is given in metres. `reference_is_input`: the reference
/// is the input poses themselves (`--poses dataset`), and the line says so instead of judging the change.
std::string DescribeApeChange(double before_m, double after_m, bool reference_is_input = false);

}  // namespace revisit
