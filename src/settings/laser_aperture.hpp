#pragma once
/// Checks a 2D laser's stated field of view against the data. Converted logs can state a wrong
/// aperture (the radish CARMEN logs converted by MRPT say 90 deg for 180 beams over 180 deg), which
/// bends every scan and makes scan matching worse than wheel odometry. When the robot turns, a scan's
/// features move by the turn in true angles but by turn / k in the stated ones (k = true / stated
/// aperture): placing the later scan's beams with each candidate k, moving them by the wheel
/// odometry and comparing with the earlier scan's ranges finds k, whatever the file says.
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "core/scan.hpp"

namespace revisit {

struct ApertureCheckConfig {
    double min_turn_deg = 8.0;         ///< [deg] turns smaller than this shift too few beams to measure
    double max_turn_deg = 45.0;        ///< [deg] larger turns leave too little overlap
    double max_translation = 1.0;      ///< [m] longer moves leave little overlap indoors
    std::size_t window = 15;           ///< earlier scans a scan is paired with
    std::size_t wanted_pairs = 40;     ///< stop collecting after this many measured turns
    double min_scale = 0.25;           ///< smallest true / stated aperture ratio searched
    double max_scale = 4.0;            ///< largest
    double scale_step = 0.005;         ///< relative step of the search
    std::size_t min_pairs = 8;         ///< fewer: no verdict
    double tolerance = 0.1;            ///< stated aperture kept when the ratio is within 1 +- this
};

struct ApertureEstimate {
    int beams = 0;
    double stated_deg = 0.0;     ///< [deg] what the file says
    double used_deg = 0.0;       ///< [deg] what the points were built with
    double measured_deg = 0.0;   ///< [deg] from the turns (ratio snapped to a multiple of 1/2 within 5%)
    double ratio = 1.0;          ///< measured / used (median over the pairs)
    double ratio_spread = 0.0;   ///< median absolute deviation of the ratio
    std::size_t pairs = 0;       ///< turns measured
    bool contradicts = false;    ///< the data says another aperture than the one used
    std::string Describe() const;
};

class ApertureChecker {
  public:
    explicit ApertureChecker(const ApertureCheckConfig& config = {}) : config_(config) {}
    /// Feeds the next scan (ignored unless it has planar beams and an odometry prior). Returns true
    /// while more scans are wanted.
    bool Add(const Scan& scan);
    bool Done() const { return ratios_.size() >= config_.wanted_pairs; }
    /// No verdict (nullopt) with fewer than min_pairs turns or without 2D beams.
    std::optional<ApertureEstimate> Estimate() const;

  private:
    struct Past {
        PlanarBeams beams;
        Eigen::Isometry3d T_odom_sensor;
    };
    ApertureCheckConfig config_;
    std::vector<Past> past_;  ///< ring of the last `window` scans
    std::vector<double> ratios_;
    int beams_ = 0;
    double stated_ = 0.0, used_ = 0.0;
};

/// The aperture scale k (true / used) under which `later`, moved by `T_earlier_later` (laser frames),
/// best matches `earlier`: the k of least mean clipped range difference over a log grid; nullopt
/// when too few beams overlap. Exposed for tests.
std::optional<double> ApertureScale(const PlanarBeams& earlier, const PlanarBeams& later, const Eigen::Isometry3d& T_earlier_later,
                                    const ApertureCheckConfig& config);

}  // namespace revisit
