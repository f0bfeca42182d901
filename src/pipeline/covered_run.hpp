#pragma once
/// The part of a run that a partial reference covers whole (RunState::reference_scans): the local
/// maps all of whose scans have a reference pose, as a run of their own with a reference pose for
/// every scan. The closure evaluation of a full reference then applies to it unchanged. A closure
/// with a map outside that part is left out of the closure metrics: judging it would need poses the
/// reference does not have, and a pose from another scan would be the wrong one.
#include <cstddef>
#include <vector>

#include "runfolder/run_state.hpp"

namespace revisit {

struct CoveredRun {
    /// Those maps' scans only, in run order, re-indexed 0..n-1 (maps, closures and comparisons too;
    /// map ids kept); has_reference() holds. Empty when no map is covered whole.
    RunState state;
    std::vector<std::size_t> scans;    ///< position in the whole run of each of state's scans
    std::size_t left_out_closures = 0; ///< the detector's and the proximity pass's candidates with a map outside
    std::size_t left_out_accepted = 0; ///< of those, closures of the final pose graph
};

/// `run` has a partial reference (has_partial_reference()); maps, closures and comparisons of other
/// sessions than the run's own are left out with the rest.
CoveredRun CoverOfReference(const RunState& run);

/// The scans of the whole run for positions of a covered run: `scans[position]`, or `position` itself
/// when `scans` is empty (the reference covers every scan).
inline std::size_t RunScan(const std::vector<std::size_t>& scans, std::size_t position) {
    return scans.empty() ? position : scans.at(position);
}

}  // namespace revisit
