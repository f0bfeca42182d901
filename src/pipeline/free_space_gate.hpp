#pragma once
/// The free-space verdict of a 2D laser's closures (optimization/free_space.hpp says why): the open
/// map's scans, each closed map's ObservedGrid, and the judgement of a pair below the overlap gate.
#include <cstddef>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "closures/local_map.hpp"
#include "config/config.hpp"
#include "optimization/free_space.hpp"
#include "optimization/refinement.hpp"

namespace revisit {

class FreeSpaceGate {
  public:
    explicit FreeSpaceGate(const PipelineConfig& config);

    /// A 2D laser's run with the check on.
    bool active() const { return active_; }
    /// Keeps a scan of the open map (before the mapper sees it: the scan that closes a map starts the next).
    void AddScan(std::size_t scan_index, const Eigen::Vector3f* points_in_sensor, std::size_t count,
                 const Eigen::Isometry3d& T_world_sensor);
    /// Makes the closed map's grid from its scans (maps close in id order).
    void CloseMap(const LocalMap& map);
    /// The settings a pair of maps `query`, `ref` is registered with: without the overlap gate when the
    /// free space judges the pair (unless the overlap gate was asked for).
    RefinementConfig Registration(const RefinementConfig& refinement, int query, int ref) const;
    /// Judges a registration made with Registration(): one below `refinement.min_overlap` stays accepted
    /// only when both maps' walls agree with what the other observed; its reason says why not.
    void Judge(RefinementResult& result, const RefinementConfig& refinement, int query, int ref) const;

  private:
    bool Judges(int query, int ref) const;
    bool active_ = false;
    bool overlap_explicit_ = false;
    double cell_ = 0.0;               ///< [m] the map voxel
    double min_agreement_ = 0.0;
    int min_observed_ = 0;            ///< wall cells each map must have observed of the other
    struct OpenScan {
        std::size_t index = 0;
        std::vector<Eigen::Vector3f> points_in_sensor;
        Eigen::Isometry3d T_world_sensor = Eigen::Isometry3d::Identity();
    };
    std::vector<OpenScan> open_scans_;
    std::vector<ObservedGrid> observed_;  ///< per closed map
};

}  // namespace revisit
