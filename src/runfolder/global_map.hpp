#pragma once
/// The corrected global map for viewing: every stored local map moved by its optimized origin,
/// downsampled, written as a binary PLY.
#include <cstddef>

#include "runfolder/run_folder.hpp"
#include "runfolder/run_state.hpp"

namespace revisit {

struct GlobalMapWritten {
    std::size_t points = 0;
    double voxel_size = 0.0;  ///< [m] the voxel it was written at (doubled from the asked one to fit max_points)
};

/// Writes run.corrected_map() at voxel_size [m], doubled until at most max_points remain (0: no cap).
GlobalMapWritten WriteGlobalMap(const RunFolder& run, const RunState& state, double voxel_size, std::size_t max_points);

}  // namespace revisit
