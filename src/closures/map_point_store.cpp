#include "closures/map_point_store.hpp"

#include <map>

namespace revisit {
namespace {

class MemoryMapStore final : public MapPointStore {
  public:
    void Put(int map_id, const std::vector<Eigen::Vector3f>& points) override { maps_[map_id] = points; }
    std::vector<Eigen::Vector3f> Get(int map_id) const override {
        const auto it = maps_.find(map_id);
        return it == maps_.end() ? std::vector<Eigen::Vector3f>{} : it->second;
    }

  private:
    std::map<int, std::vector<Eigen::Vector3f>> maps_;
};

}  // namespace

std::unique_ptr<MapPointStore> MakeMemoryMapStore() { return std::make_unique<MemoryMapStore>(); }

}  // namespace revisit
