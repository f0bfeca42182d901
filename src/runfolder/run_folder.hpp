#pragma once
/// The files of one run. Every stage writes through these names; `revisit report` and `revisit eval`
/// read the same names, so a finished run can be re-evaluated and redrawn without recomputing.
#include <filesystem>
#include <string>

namespace revisit {

class RunFolder {
  public:
    explicit RunFolder(std::filesystem::path root) : root_(std::move(root)) {}

    /// Creates the folder; refuses a non-empty one unless `force` (DatasetError names it). With
    /// `force`, an earlier run's results there are removed first (RemoveEarlierResults).
    static RunFolder Create(const std::filesystem::path& root, bool force);
    /// Removes the files a run writes (by their names: run.json, closures.csv, maps/map_*.rvmap, report
    /// pages, ...) from `root`, so nothing of an earlier run is read as a new one's; other files stay.
    static void RemoveEarlierResults(const std::filesystem::path& root);
    /// Opens an existing run for reading; throws DatasetError when it is not a run folder.
    static RunFolder Open(const std::filesystem::path& root);

    /// `reports/<dataset name>-<YYYYmmdd-HHMMSS>` under `parent`, plus a `latest` symlink next to it.
    static std::filesystem::path DefaultPath(const std::filesystem::path& parent, const std::filesystem::path& dataset);
    static void UpdateLatestLink(const std::filesystem::path& run);

    const std::filesystem::path& root() const { return root_; }
    std::filesystem::path config() const { return root_ / "config.yaml"; }
    std::filesystem::path run_info() const { return root_ / "run.json"; }
    std::filesystem::path odometry_kitti() const { return root_ / "poses_odometry_kitti.txt"; }
    std::filesystem::path odometry_tum() const { return root_ / "poses_odometry_tum.txt"; }
    std::filesystem::path corrected_kitti() const { return root_ / "poses_corrected_kitti.txt"; }
    std::filesystem::path corrected_tum() const { return root_ / "poses_corrected_tum.txt"; }
    std::filesystem::path reference_tum() const { return root_ / "poses_reference_tum.txt"; }
    std::filesystem::path closures_csv() const { return root_ / "closures.csv"; }
    std::filesystem::path local_maps_csv() const { return root_ / "local_maps.csv"; }
    std::filesystem::path metrics_json() const { return root_ / "metrics.json"; }
    std::filesystem::path timings_json() const { return root_ / "timings.json"; }
    std::filesystem::path database() const { return root_ / "database.bin"; }
    std::filesystem::path corrected_map() const { return root_ / "map_corrected.ply"; }
    std::filesystem::path maps_dir() const { return root_ / "maps"; }
    /// Downsampled points of local map `id` in its own frame (runfolder/map_points_file.hpp).
    std::filesystem::path map_points(int id) const;
    /// The same as run folders written before the compact format kept them (KITTI .bin).
    std::filesystem::path legacy_map_points(int id) const;
    /// The density image of local map `id` (8-bit PNG) and its origin/resolution sidecar.
    std::filesystem::path map_density(int id) const;
    std::filesystem::path report_dir() const { return root_ / "report"; }
    std::filesystem::path report_index() const { return report_dir() / "index.html"; }

  private:
    std::filesystem::path root_;
};

}  // namespace revisit
