#pragma once
/// `revisit batch --engine local`: the plan's runs on this machine, at most `jobs` at a time (each a
/// child process writing its own log), then the merge.
#include <ostream>
#include <vector>

#include "fleet/batch_plan.hpp"

namespace revisit {

struct LocalOutcome {
    std::vector<std::size_t> failed;  ///< task indices whose run did not finish
    int merge_exit = -1;              ///< -1: not run (a run failed)
};

/// Runs the tasks `indices`, then (when all of the plan's runs are finished) the merge.
LocalOutcome RunLocally(const BatchPlan& plan, const std::vector<std::size_t>& indices, int jobs, std::ostream& log);

}  // namespace revisit
