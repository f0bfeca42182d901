#pragma once
/// Where closed local maps' points wait until a later map closes with them.
#include <memory>
#include <vector>

#include <Eigen/Core>

namespace revisit {

/// Memory by default; the run folder for `revisit run` (runfolder/folder_map_store.hpp), so that memory
/// stays bounded by one local map and the database.
class MapPointStore {
  public:
    virtual ~MapPointStore() = default;
    virtual void Put(int map_id, const std::vector<Eigen::Vector3f>& points_in_map) = 0;
    virtual std::vector<Eigen::Vector3f> Get(int map_id) const = 0;
};
std::unique_ptr<MapPointStore> MakeMemoryMapStore();

}  // namespace revisit
