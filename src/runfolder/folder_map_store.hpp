#pragma once
/// Local map points kept in the run folder (maps/map_NNNN.bin) instead of memory.
#include <memory>

#include "closures/map_point_store.hpp"
#include "runfolder/run_folder.hpp"

namespace revisit {

std::unique_ptr<MapPointStore> MakeFolderMapStore(const RunFolder& run);
/// Reads the stored points of one map (as written by the folder store).
std::vector<Eigen::Vector3f> ReadMapPoints(const RunFolder& run, int map_id);

}  // namespace revisit
