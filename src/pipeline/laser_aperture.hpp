#pragma once
/// Checks a 2D laser's stated field of view against the data. Converted logs can state a wrong
/// aperture (the radish CARMEN logs converted by MRPT say 90 deg for 180 beams over 180 deg), which
/// bends every scan and makes scan matching worse than wheel odometry. When the robot turns on the
/// spot, the range profile shifts by (turn / true beam step) beams; the wheel odometry's turn over
/// the shift measured in the data gives the true step, whatever the file says.
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "core/scan.hpp"

namespace revisit {

struct ApertureCheckConfig {
    double min_turn_deg = 8.0;         ///< [deg] turns smaller than this shift too few beams to measure
    double max_turn_deg = 45.0;        ///< [deg] larger turns leave too little overlap
    double max_translation = 0.3;      ///< [m] pairs that also move are not pure turns
    std::size_t window = 15;           ///< earlier scans a scan is paired with
    std::size_t wanted_pairs = 40;     ///< stop collecting after this many measured turns
    std::size_t min_pairs = 8;         ///< fewer: no verdict
    double tolerance = 0.1;            ///< stated aperture kept when the ratio is within 1 +- this
};

struct ApertureEstimate {
    int beams = 0;
    double stated_deg = 0.0;     ///< [deg] what the file says
    double used_deg = 0.0;       ///< [deg] what the points were built with
    double measured_deg = 0.0;   ///< [deg] from the turns (snapped to 5 deg when within 2.5%)
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
        std::vector<float> ranges;
        Eigen::Isometry3d T_odom_sensor;
    };
    ApertureCheckConfig config_;
    std::vector<Past> past_;  ///< ring of the last `window` scans
    std::vector<double> ratios_;
    int beams_ = 0;
    double stated_ = 0.0, used_ = 0.0;
};

/// The shift s [beams, sub-beam] that best maps `later` onto `earlier` (later[i] ~ earlier[i + s]),
/// searched over |s| <= max_shift with a robust mean absolute range difference; nullopt when the
/// overlap is too small. Exposed for tests.
std::optional<double> ProfileShift(const std::vector<float>& earlier, const std::vector<float>& later, int max_shift);

}  // namespace revisit
