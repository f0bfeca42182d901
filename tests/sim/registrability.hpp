#pragma once
/// Measurements that say whether scans register like real ones (issue 15): scan statistics
/// (ground roughness and slope variation, volumetric clutter) and the behaviour of the odometry's
/// scan-to-map ICP (METHOD.md section 1) against a map of the preceding scans at their true poses:
/// correspondences, residuals, conditioning of J^T J, the cost along the true motion and where ICP
/// ends when it starts from zero motion. Used by registrability_test.cpp to print the table of
/// src/sim/README.md for real KITTI scans and simulated ones.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <string>
#include <vector>

#include "core/trajectory.hpp"

namespace revisit {

/// A sequence of consecutive scans (sensor frame) with their true poses T_world_sensor.
struct ProbeSequence {
    std::string name;
    std::vector<std::vector<Eigen::Vector3f>> scans;
    Poses poses;
    double sensor_height = 1.73;  ///< [m] above the ground (to separate ground points)
};

struct ScanStatistics {
    double ground_roughness = 0.0;   ///< [m] median RMS residual of planes fitted to ground points in 1 m cells
    double ground_tilt_spread = 0.0; ///< [deg] std of the ground normal's tilt over 4 m cells (5-30 m)
    double ground_share = 0.0;       ///< points within 0.3 m of the ground height below the sensor
    double scatter_share = 0.0;      ///< 0.5 m voxels (>= 6 points) whose points are not on a plane (3rd eigen sigma > 5 cm)
};

/// ICP behaviour, averaged over the probed frames. Odometry defaults: v = 1 m voxels, crop 5-100 m.
struct RegistrationProbe {
    double correspondences = 0.0;      ///< source points with a map neighbour within 3 sigma at the true pose
    double ground_correspondence_share = 0.0;
    double residual_median = 0.0;      ///< [m] at the true pose
    double residual_p90 = 0.0;         ///< [m]
    double jtj_min_eigen = 0.0;        ///< smallest eigenvalue of sum w J^T J / n at the true pose (kernel weights w)
    double jtj_condition = 0.0;        ///< its largest / smallest eigenvalue
    double along_information = 0.0;    ///< 1 / (u^T (H/n)^-1 u), u the true direction of travel: how well the
                                       ///< motion along the road is pinned once rotation and the other axes are free
    std::array<double, 7> cost{};      ///< robust cost at alpha * true motion, alpha = -0.5..1.0 step 0.25, / cost(0)
    double zero_is_local_minimum = 0.0;///< share of frames where cost(+-10 cm along the motion) > cost(0)
    double recovered = 0.0;            ///< ICP from zero motion: estimated / true forward motion (1 = right)
    int frames = 0;
};

ScanStatistics DescribeScans(const ProbeSequence& sequence);
/// Probes frames k = history .. n-1, each against the map of its `history` predecessors.
/// `sigma` [m]: the adaptive threshold (kernel sigma / 3, correspondences within 3 sigma).
RegistrationProbe ProbeRegistration(const ProbeSequence& sequence, int history, double sigma);

}  // namespace revisit
