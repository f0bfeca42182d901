#include "runfolder/folder_map_store.hpp"

#include "io/cloud_files.hpp"

namespace revisit {
namespace {

class FolderMapStore final : public MapPointStore {
  public:
    explicit FolderMapStore(RunFolder run) : run_(std::move(run)) {}
    void Put(int map_id, const std::vector<Eigen::Vector3f>& points) override {
        Scan scan;
        scan.points = points;
        SaveKittiBin(run_.map_points(map_id), scan);
    }
    std::vector<Eigen::Vector3f> Get(int map_id) const override { return ReadMapPoints(run_, map_id); }

  private:
    RunFolder run_;
};

}  // namespace

std::unique_ptr<MapPointStore> MakeFolderMapStore(const RunFolder& run) { return std::make_unique<FolderMapStore>(run); }

std::vector<Eigen::Vector3f> ReadMapPoints(const RunFolder& run, int map_id) {
    return LoadKittiBin(run.map_points(map_id)).points;
}

}  // namespace revisit
