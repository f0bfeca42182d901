#pragma once
/// Local map points kept in the run folder (maps/map_NNNN.rvmap) instead of memory.
#include <memory>

#include "closures/map_point_store.hpp"
#include "runfolder/run_folder.hpp"

namespace revisit {

/// Stores maps on the grid of `step_m` (MapPointStep(output.map_voxel)); the chain gives them already
/// snapped (SnapToMapPointGrid), so what it reads back is what it stored.
std::unique_ptr<MapPointStore> MakeFolderMapStore(const RunFolder& run, double step_m);
/// Whether the run stored local map `map_id`'s points (in either format).
bool HasMapPoints(const RunFolder& run, int map_id);
/// Reads the stored points of one map (as written by the folder store; a run folder written before the
/// compact format: its KITTI .bin). A damaged file is a DatasetError naming it.
std::vector<Eigen::Vector3f> ReadMapPoints(const RunFolder& run, int map_id);

}  // namespace revisit
