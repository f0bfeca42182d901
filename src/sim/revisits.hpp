#pragma once
/// Revisits found in a ground-truth trajectory: stretches where the sensor comes back close to
/// where it was much earlier. Used to check planned routes and to describe simulated sequences.
#include <cstddef>
#include <vector>

#include "core/trajectory.hpp"

namespace revisit {

struct RevisitConfig {
    double radius = 8.0;          ///< [m] closer than this to an earlier pose counts as a return
    double min_gap = 200.0;       ///< [m] travelled between the earlier pose and the return
    double min_length = 20.0;     ///< [m] a return shorter than this is not counted
    double opposite_angle = 2.0;  ///< [rad] heading difference above which a return is "opposite" (~115 deg)
};

struct Revisit {
    std::size_t first = 0;              ///< first pose index of the return
    std::size_t last = 0;               ///< last pose index of the return
    std::size_t reference = 0;          ///< earlier pose closest to the return's closest pose
    double min_distance = 0.0;          ///< [m]
    double heading_difference = 0.0;    ///< [rad] between the sensors' x axes projected on the XY plane, mid-return, [0, pi]
    bool opposite = false;
};

std::vector<Revisit> FindRevisits(const Poses& poses, const RevisitConfig& config = {});

}  // namespace revisit
