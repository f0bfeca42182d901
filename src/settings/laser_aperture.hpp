#pragma once
/// Checks a 2D laser's stated field of view against the beams' own geometry. Converted logs can state a
/// wrong aperture (the radish CARMEN logs converted by MRPT say 90 deg for 180 beams over 180 deg),
/// which bends every wall and makes scan matching worse than wheel odometry. Walls are straight and
/// consecutive scans agree only when the beams are placed at the right angles: for each standard
/// aperture (and the stated one), pairs of nearby scans are built with it and matched by a correlative
/// scan match (odometry/correlative_matcher.hpp, around the wheel odometry's motion when there is
/// one, which fixes the turn); the aperture under which they agree best is the data's. The file's value
/// is changed only when a candidate beats it on the pairs beyond doubt (a paired test); among those the
/// data cannot tell apart, the smallest change is taken.
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "core/scan.hpp"

namespace revisit {

struct ApertureCheckConfig {
    /// [deg] the apertures of common 2D lasers (SICK LMS 2xx: 180 / 180.5 with 181 / 361 beams;
    /// 190; Hokuyo: 240, 270), tried besides the stated one.
    std::vector<double> standard_deg = {180.0, 180.5, 190.0, 240.0, 270.0};
    double min_turn_deg = 5.0;        ///< [deg] with wheel odometry, a pair needs this much turn to say something
    double max_translation = 1.0;     ///< [m] longer moves leave little overlap indoors
    double max_turn_deg = 45.0;       ///< [deg] larger turns leave too little overlap
    std::size_t window = 15;          ///< earlier scans a scan is paired with
    std::size_t wanted_pairs = 40;    ///< stop collecting after this many pairs
    std::size_t min_pairs = 12;       ///< fewer: no verdict
    /// A paired t statistic of the score gain at least this: the gain is no accident of the pairs
    /// (the usual "beyond doubt" of a one-sided test, p ~ 1e-4 at 40 pairs).
    double min_t = 4.0;
};

struct ApertureEstimate {
    int beams = 0;
    double stated_deg = 0.0;     ///< [deg] what the file says
    double used_deg = 0.0;       ///< [deg] what the points were built with
    double measured_deg = 0.0;   ///< [deg] the candidate the pairs agree best under
    double measured_score = 0.0;  ///< mean match score of the pairs under it, in [0, 1]
    double used_score = 0.0;      ///< under the used aperture
    double t_used = 0.0;          ///< paired t statistic of measured over used
    double t_runner_up = 0.0;     ///< of measured over the next best candidate
    double runner_up_deg = 0.0;   ///< [deg] that candidate
    std::size_t pairs = 0;        ///< scan pairs measured
    bool contradicts = false;     ///< the data decides for another aperture than the one used
    /// The data prefers another aperture, but not beyond doubt: kept, with a warning.
    bool doubtful = false;
    std::string Describe() const;
};

class ApertureChecker {
  public:
    explicit ApertureChecker(const ApertureCheckConfig& config = {}) : config_(config) {}
    /// Feeds the next scan (ignored unless it has planar beams). Returns true while more scans are wanted.
    bool Add(const Scan& scan);
    bool Done() const { return pair_scores_.size() >= config_.wanted_pairs; }
    /// No verdict (nullopt) with fewer than min_pairs pairs or without 2D beams.
    std::optional<ApertureEstimate> Estimate() const;

  private:
    struct Past {
        PlanarBeams beams;
        std::optional<Eigen::Isometry3d> T_odom_sensor;
        std::size_t index = 0;
    };
    ApertureCheckConfig config_;
    std::vector<double> candidates_deg_;           ///< the used aperture first, then the standard ones
    std::vector<Past> past_;                       ///< ring of the last `window` scans
    std::vector<std::vector<double>> pair_scores_;  ///< per pair, the score under each candidate
    int beams_ = 0;
    double stated_ = 0.0, used_ = 0.0;
};

/// Mean likelihood in [0, 1] of `later`'s beams, placed with `aperture` [rad], against `earlier`'s
/// placed the same way, at the best pose a correlative match finds within the windows around
/// `T_earlier_later` (the motion between the laser frames). Exposed for tests.
double PairScore(const PlanarBeams& earlier, const PlanarBeams& later, double aperture, const Eigen::Isometry3d& T_earlier_later,
                 double linear_window, double angular_window);

}  // namespace revisit
