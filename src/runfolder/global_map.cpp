#include "runfolder/global_map.hpp"

#include "io/cloud_files.hpp"
#include "optimization/global_map.hpp"
#include "runfolder/folder_map_store.hpp"

namespace revisit {

GlobalMapWritten WriteGlobalMap(const RunFolder& run, const RunState& state, double voxel_size, std::size_t max_points) {
    GlobalMapBuilder builder(voxel_size, max_points);
    for (const auto& map : state.maps) builder.Add(ReadMapPoints(run, map.id), map.T_world_map_corrected);
    SavePly(run.corrected_map(), builder.Points());
    return {builder.size(), builder.voxel_size()};
}

}  // namespace revisit
