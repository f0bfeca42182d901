#pragma once
/// The corrected global map for viewing: every stored local map moved by its optimized origin,
/// downsampled, written as a binary PLY.
#include "runfolder/run_folder.hpp"
#include "runfolder/run_state.hpp"

namespace revisit {

/// Writes run.corrected_map(); returns the number of points written.
std::size_t WriteGlobalMap(const RunFolder& run, const RunState& state, double voxel_size);

}  // namespace revisit
