#pragma once
/// The 2D laser scans of a planar run, kept per local map in the run folder (maps/scans_NNNN.bin), so
/// that the occupancy grid can trace every beam from where it was taken once the trajectory is
/// corrected. Written as each map closes: memory holds the open map's scans only.
#include <cstddef>
#include <vector>

#include <Eigen/Core>

#include "runfolder/run_folder.hpp"

namespace revisit {

/// One scan's returns in its sensor frame (x, y; a planar run's z is 0).
struct PlanarScan {
    std::size_t position = 0;  ///< among the scans processed (index into the run's trajectories)
    std::vector<Eigen::Vector2f> points_in_sensor;  ///< [m]
};

/// maps/scans_NNNN.bin of local map `map_id`.
std::filesystem::path PlanarScansFile(const RunFolder& run, int map_id);

/// Collects the scans of the open local map and writes them when the map closes.
class PlanarScanWriter {
  public:
    explicit PlanarScanWriter(RunFolder run) : run_(std::move(run)) {}
    /// Adds a scan of map `map_id` (maps are numbered in order; a new id writes the previous map's scans).
    void Add(int map_id, std::size_t position, const std::vector<Eigen::Vector3f>& points_in_sensor);
    /// Writes the last map's scans.
    void Finish();

  private:
    void Flush();
    RunFolder run_;
    int map_id_ = -1;
    std::vector<PlanarScan> scans_;
};

/// Reads maps/scans_NNNN.bin; an empty list when the run stored none for that map (a 3D run). Throws
/// DatasetError naming the file and the byte offset of damage.
std::vector<PlanarScan> ReadPlanarScans(const RunFolder& run, int map_id);

}  // namespace revisit
