#include "pipeline/global_map.hpp"

#include <tsl/robin_set.h>

#include <cmath>

#include "io/cloud_files.hpp"
#include "pipeline/folder_map_store.hpp"

namespace revisit {

std::size_t WriteGlobalMap(const RunFolder& run, const RunState& state, double voxel_size) {
    struct KeyHash {
        std::size_t operator()(const Eigen::Vector3i& k) const {
            return (static_cast<std::size_t>(k.x()) * 73856093u) ^ (static_cast<std::size_t>(k.y()) * 19349669u) ^
                   (static_cast<std::size_t>(k.z()) * 83492791u);
        }
    };
    tsl::robin_set<Eigen::Vector3i, KeyHash> occupied;
    std::vector<Eigen::Vector3f> points;
    for (const auto& map : state.maps) {
        const Eigen::Isometry3f T = map.T_world_map_corrected.cast<float>();
        for (const auto& p_map : ReadMapPoints(run, map.id)) {
            const Eigen::Vector3f p = T * p_map;
            const Eigen::Vector3i key = (p / static_cast<float>(voxel_size)).array().floor().cast<int>();
            if (occupied.insert(key).second) points.push_back(p);  // the first point per voxel, deterministic
        }
    }
    SavePly(run.corrected_map(), points);
    return points.size();
}

}  // namespace revisit
