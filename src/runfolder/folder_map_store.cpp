#include "runfolder/folder_map_store.hpp"

#include "io/cloud_files.hpp"
#include "runfolder/map_points_file.hpp"

namespace revisit {
namespace {

class FolderMapStore final : public MapPointStore {
  public:
    FolderMapStore(RunFolder run, double step_m) : run_(std::move(run)), step_m_(step_m) {}
    void Put(int map_id, const std::vector<Eigen::Vector3f>& points) override { SaveMapPoints(run_.map_points(map_id), points, step_m_); }
    std::vector<Eigen::Vector3f> Get(int map_id) const override { return ReadMapPoints(run_, map_id); }

  private:
    RunFolder run_;
    double step_m_;
};

}  // namespace

std::unique_ptr<MapPointStore> MakeFolderMapStore(const RunFolder& run, double step_m) {
    return std::make_unique<FolderMapStore>(run, step_m);
}

bool HasMapPoints(const RunFolder& run, int map_id) {
    return std::filesystem::exists(run.map_points(map_id)) || std::filesystem::exists(run.legacy_map_points(map_id));
}

std::vector<Eigen::Vector3f> ReadMapPoints(const RunFolder& run, int map_id) {
    const auto file = run.map_points(map_id);
    if (!std::filesystem::exists(file) && std::filesystem::exists(run.legacy_map_points(map_id))) {
        return LoadKittiBin(run.legacy_map_points(map_id)).points;
    }
    return LoadMapPoints(file);
}

}  // namespace revisit
