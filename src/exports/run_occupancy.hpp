#pragma once
/// A run's occupancy grid (occupancy.png + occupancy.yaml) from its corrected trajectory, for
/// navigation stacks (map_server, nav2).
#include <cstddef>
#include <filesystem>
#include <functional>

#include "config/config.hpp"
#include "exports/occupancy_grid.hpp"
#include "runfolder/run_folder.hpp"
#include "runfolder/run_state.hpp"

namespace revisit {

/// Called after each map of each of the grid's two passes (the extent, then the cells) with how many
/// of `total` (twice the maps) are done: minutes on a long run.
using OccupancyProgress = std::function<void(std::size_t done, std::size_t total)>;

/// 2D lasers (the run stored its scans, maps/scans_*.bin): every beam traced from where it was taken,
/// at the scan's corrected pose. 3D runs: each corrected local map's points in a band of heights above
/// its own levelled ground mark occupied cells, its ground points free ones, in the first map's
/// levelled frame. Throws DatasetError for a damaged run folder.
OccupancyGrid BuildRunOccupancy(const RunFolder& run, const RunState& state, const PipelineConfig& config,
                                const OccupancyProgress& on_map = {});

/// Writes `image` (PNG, or PGM when its name ends in .pgm) and the YAML beside it (same name, .yaml);
/// returns the YAML's path.
std::filesystem::path WriteRunOccupancy(const RunFolder& run, const RunState& state, const PipelineConfig& config,
                                        const std::filesystem::path& image, const OccupancyProgress& on_map = {});

}  // namespace revisit
