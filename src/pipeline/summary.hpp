#pragma once
/// The table `revisit run` prints at the end: counts, time per stage, and metrics when evaluated.
#include <optional>
#include <ostream>

#include "pipeline/evaluate.hpp"
#include "pipeline/run_state.hpp"

namespace revisit {

void PrintRunSummary(std::ostream& out, const RunState& state, const std::optional<RunEvaluation>& evaluation);

}  // namespace revisit
