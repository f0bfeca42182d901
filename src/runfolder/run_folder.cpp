#include "runfolder/run_folder.hpp"

#include <cstring>
#include <ctime>
#include <iomanip>
#include <sstream>

#include "core/error.hpp"
#include "core/owned_files.hpp"
#include "io/output_folder.hpp"

namespace revisit {
namespace fs = std::filesystem;

namespace {
/// A file name a run writes at the top of its folder (run_folder.hpp's names, the evaluation's files).
bool IsRunResultName(const std::string& name) {
    static const char* const kNames[] = {"config.yaml", "run.json", "run_options.json", "poses_odometry_kitti.txt",
                                         "poses_odometry_tum.txt", "poses_corrected_kitti.txt", "poses_corrected_tum.txt",
                                         "poses_reference_tum.txt", "closures.csv", "local_maps.csv", "comparisons.csv",
                                         "metrics.json", "timings.json", "database.bin", "map_corrected.ply",
                                         "comparison.md", "ground_truth_closures.txt", "pose_graph.g2o", "closures.json",
                                         "occupancy.png", "occupancy.pgm", "occupancy.yaml"};  // .pgm: older runs
    for (const char* n : kNames) {
        if (name == n) return true;
    }
    return name.rfind("pr_curve_", 0) == 0 && fs::path(name).extension() == ".csv";
}
}  // namespace

RunFolder RunFolder::Create(const fs::path& root, bool force) {
    PrepareOutputFolder(root, force);
    // With --force into an earlier folder: a linked subfolder would take the results outside the run.
    RefuseLinkedFolder(root / "maps");
    RefuseLinkedFolder(root / "closures");
    RefuseLinkedFolder(root / "report");
    RemoveEarlierResults(root);
    fs::create_directories(root / "maps");
    return RunFolder(root);
}

void RunFolder::RemoveEarlierResults(const fs::path& root) {
    // What an earlier run wrote and this one may not (no reference: no metrics; fewer maps or
    // closures): left there it would be read as this run's. Only revisit's own names go.
    RemoveOwnFilesIf(root, IsRunResultName);
    RemoveOwnFolder(root / "maps", {".rvmap", ".bin", ".png"});
    RemoveOwnFolder(root / "closures", {".json"});
    RemoveOwnFolder(root / "report", {".html", ".png", ".svg"});
}

RunFolder RunFolder::Open(const fs::path& root) {
    RunFolder run(root);
    if (!fs::is_directory(root)) throw DatasetError(root, "no such run folder");
    if (!fs::exists(run.run_info())) throw DatasetError(root, "not a revisit run folder (no run.json)");
    return run;
}

fs::path RunFolder::DefaultPath(const fs::path& parent, const fs::path& dataset) {
    const std::time_t now = std::time(nullptr);
    std::tm local{};
    localtime_r(&now, &local);
    std::ostringstream name;
    fs::path base = dataset.filename().empty() ? dataset.parent_path().filename() : dataset.filename();
    std::string stem = base.string();
    for (const char* suffix : {".gz", ".rawlog"}) {
        if (stem.size() > std::strlen(suffix) && stem.compare(stem.size() - std::strlen(suffix), std::string::npos, suffix) == 0) {
            stem.resize(stem.size() - std::strlen(suffix));
        }
    }
    for (char& c : stem) {
        if (c == ' ' || c == '/' || c == ':') c = '_';
    }
    name << (stem.empty() ? "run" : stem) << '-' << std::put_time(&local, "%Y%m%d-%H%M%S");
    return parent / name.str();
}

void RunFolder::UpdateLatestLink(const fs::path& run) {
    const fs::path link = run.parent_path() / "latest";
    std::error_code ec;
    if (fs::is_symlink(link)) fs::remove(link, ec);
    if (!fs::exists(link)) fs::create_directory_symlink(run.filename(), link, ec);  // best effort
}

fs::path RunFolder::map_points(int id) const {
    std::ostringstream name;
    name << "map_" << std::setw(4) << std::setfill('0') << id << ".rvmap";
    return maps_dir() / name.str();
}

fs::path RunFolder::legacy_map_points(int id) const { return fs::path(map_points(id)).replace_extension(".bin"); }

fs::path RunFolder::map_density(int id) const {
    std::ostringstream name;
    name << "map_" << std::setw(4) << std::setfill('0') << id << "_density.png";
    return maps_dir() / name.str();
}

}  // namespace revisit
