#pragma once
/// The refinement's RMS gate, measured on this run's own maps (METHOD.md section 7, "The RMS gate
/// follows the odometry").
///
/// Why: the RMS of a registration of two local maps is not only the sensor's noise. Each map is built
/// from its scans at the odometry's poses, so an odometry that drifts within a map (a 1% scale error
/// puts a wall seen from 100 m of travel in two places 1 m apart) smears it, and two right maps then
/// register with a higher RMS than the fixed gate expects. Consecutive maps overlap by construction
/// (the end of one and the start of the next see the same street), so registering each map with its
/// predecessor at the odometry's relative pose measures the RMS that a true overlap shows under this
/// odometry, once per map. The gate is a multiple of the median of those RMS, never below the
/// configured one: good odometry keeps today's gate exactly.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <vector>

#include "optimization/refinement.hpp"

namespace revisit {

class SmearGate {
  public:
    /// `factor`: the gate's multiple of the median (<= 0: the configured gate, nothing measured).
    explicit SmearGate(double factor = 0.0) : factor_(factor) {}

    bool active() const { return factor_ > 0.0; }
    /// One consecutive pair's registration (ignored when it did not register: too few correspondences).
    void Add(const RefinementResult& consecutive, int min_correspondences);
    /// [m] The gate for the next verdicts: max(configured, factor x median of the measured RMS).
    double MaxRms(double configured) const;
    /// [m] Median of the measured RMS (0 when none).
    double MedianRms() const;
    const std::vector<double>& measured() const { return rms_; }

  private:
    double factor_;
    std::vector<double> rms_;  ///< [m] in map order
};

/// Registers map `query` onto its predecessor `ref` from the odometry's relative pose, for the gate:
/// the odometry knows the height (no vertical search), and the verdict is not used.
RefinementResult RegisterConsecutive(const std::vector<Eigen::Vector3d>& ref_points_in_ref,
                                     const std::vector<Eigen::Vector3d>& query_points_in_query,
                                     const Eigen::Isometry3d& T_query_ref_odometry, const RefinementConfig& config);
/// The same with the query map prepared; identical results when `query.SamePlanesAs(UnitZ)` (the
/// vertical the points alone are registered with).
RefinementResult RegisterConsecutive(const std::vector<Eigen::Vector3d>& ref_points_in_ref, const RefinementQuery& query,
                                     const Eigen::Isometry3d& T_query_ref_odometry, const RefinementConfig& config);

}  // namespace revisit
