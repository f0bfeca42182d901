#pragma once
/// The refinement settings a run verifies its closures with: the configured ones, with the RMS gate
/// raised when this run's own odometry smears its maps (optimization/smear_gate.hpp says why).
#include <cstddef>
#include <optional>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "config/config.hpp"
#include "optimization/smear_gate.hpp"
#include "runfolder/run_state.hpp"

namespace revisit {

class RefinementGate {
  public:
    explicit RefinementGate(const PipelineConfig& config);

    /// Whether consecutive maps are registered at all: only under the default 3D gate (a gate chosen
    /// otherwise, as 2D lasers' two map voxels, a preset or --set, has its own calibration).
    bool active() const { return smear_gate_.active(); }
    /// Registers the map that just closed (`query`, first scan `first_scan`) onto its predecessor at
    /// the odometry's relative pose, and lets the gate follow the RMS that overlap shows.
    /// `prepared`: the query map's planes when already made (used where they are the ones its points
    /// give under the registration's vertical, RefinementQuery::SamePlanesAs; the result is the same).
    void AddConsecutive(const std::vector<Eigen::Vector3d>& ref_points_in_ref,
                        const std::vector<Eigen::Vector3d>& query_points_in_query,
                        const Eigen::Isometry3d& T_query_ref_odometry, std::size_t first_scan,
                        const RefinementQuery* prepared = nullptr);
    /// The refinement's settings for the next verdicts.
    RefinementConfig Refinement() const;
    /// The raised gate as a setting update for run.json (none when it stayed at the configured value).
    std::optional<SettingUpdate> Update() const;

  private:
    RefinementConfig refinement_;
    double factor_ = 0.0;
    SmearGate smear_gate_;
    std::optional<std::size_t> raised_at_;  ///< first scan of the first map verified above the configured gate
};

}  // namespace revisit
