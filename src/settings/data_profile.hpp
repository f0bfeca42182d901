#pragma once
/// What the first scans of a sequence show about the sensor and the scene: the description from
/// which the automatic settings are derived (src/settings/auto_settings.hpp). Streaming: feed scans
/// as they arrive; the profile needs only the first few.
#include <cstddef>
#include <string>
#include <vector>

#include "core/scan.hpp"
#include "settings/motion_profile.hpp"

namespace revisit {

struct DataProfile {
    std::size_t scans = 0;          ///< scans looked at
    bool planar = false;            ///< every point at z = 0: a 2D laser
    double points_per_scan = 0.0;   ///< median over the scans
    double range_p01 = 0.0;         ///< [m] 1st percentile of the point ranges
    double range_p50 = 0.0;         ///< [m] median range: the scene's scale
    double range_p95 = 0.0;         ///< [m]
    double range_p99 = 0.0;         ///< [m]
    double range_max = 0.0;         ///< [m]
    /// The first scan (its index in the sequence) with a point beyond kMaxPlausibleRange, and that
    /// point's range [m]; far_range 0: none. The percentiles above are robust to a few such points.
    std::size_t far_scan = 0;
    double far_range = 0.0;
    double horizontal_fov_deg = 0.0;  ///< [deg] azimuth covered (1-degree bins with points)
    double vertical_fov_deg = 0.0;    ///< [deg] elevation span, 1st to 99th percentile (0 for 2D lasers)
    /// [deg] mean elevation step between the sensor's rings (vertical FOV / rings), 0 when the points do
    /// not lie on distinct rings (a rosette or other non-repetitive pattern, a 2D laser).
    double ring_spacing_deg = 0.0;
    int rings = 0;                    ///< distinct elevation rings seen (0: none)
    double scan_period = 0.0;       ///< [s] median time between scans (0: unknown)
    bool has_point_times = false;   ///< per-point times (deskewing possible)
    bool has_odometry_prior = false;
    /// Registration voxel candidates [m] and the median number of points a scan keeps after the
    /// odometry's 1.5 v source downsampling at each (METHOD.md section 1).
    std::vector<double> voxel_candidates;
    std::vector<double> source_points;
    /// [deg] tilt of the ground plane seen in the sensor frame (median over the first scans; -1: no
    /// ground found): a handheld or tilted sensor, whose maps must be levelled before projecting.
    double ground_tilt_deg = -1.0;
    /// How fast the platform moves (measured after the odometry's settings are chosen; see
    /// ConfigureFromData).
    MotionProfile motion;

    bool empty() const { return scans == 0; }
    /// One line per fact, for `revisit info` and the run log.
    std::vector<std::string> Describe() const;
};

/// [m] No lidar or laser measures beyond this: a point farther away is damage or a unit mistake,
/// reported with its scan (the profile's memory does not depend on it either way).
constexpr double kMaxPlausibleRange = 10'000.0;

/// Map voxel sizes the automatic settings choose from [m].
const std::vector<double>& VoxelCandidates();

/// Accumulates scans (only a sample of each scan's points is kept) and summarizes them.
class DataProfiler {
  public:
    /// `max_scans`: scans to look at; empty scans do not count.
    explicit DataProfiler(std::size_t max_scans = 10) : max_scans_(max_scans) {}

    /// Returns true while more scans are wanted.
    bool Add(const Scan& scan);
    bool Done() const { return scans_ >= max_scans_; }
    DataProfile Profile() const;

  private:
    void NoteFarPoint(const Scan& scan, double range);

    std::size_t max_scans_;
    std::size_t scans_ = 0;
    std::vector<double> ranges_;      ///< sampled point ranges [m]
    std::vector<double> elevations_;  ///< sampled [deg]
    std::vector<std::size_t> elevation_histogram_;  ///< every point of the first scans, 0.1 deg bins from -90 deg
    std::vector<bool> azimuth_bins_ = std::vector<bool>(360, false);
    std::vector<double> points_per_scan_;
    std::vector<double> timestamps_;
    std::vector<std::vector<double>> source_points_;  ///< per voxel candidate, per scan
    std::vector<double> ground_tilts_;                ///< [deg] per scan with a ground plane
    std::size_t far_scan_ = 0;
    double far_range_ = 0.0;
    bool planar_ = true;
    bool point_times_ = false;
    bool odometry_prior_ = false;
};

}  // namespace revisit
