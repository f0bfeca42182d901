#pragma once
/// Overview pictures of a whole run: corrected map, trajectories and closures (issue 8, "Pictures").
#include "render/scene_common.hpp"

#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <vector>

namespace revisit {

/// A closure drawn where the trajectory came back: the revisiting (query) scans' position on the corrected
/// trajectory, where the two maps coincide once corrected.
struct ClosureMark {
    Eigen::Vector3d position = Eigen::Vector3d::Zero();  ///< [m] world
    bool accepted = false;
};

/// Everything an overview draws; positions in the world frame [m]. Empty members are simply not drawn.
struct OverviewData {
    std::vector<Eigen::Vector3f> map_points;  ///< corrected global map (the caller may decimate it)
    std::vector<Eigen::Vector3d> odometry;    ///< odometry positions, one per scan
    std::vector<Eigen::Vector3d> corrected;   ///< corrected positions
    std::vector<Eigen::Vector3d> reference;   ///< ground-truth positions
    std::vector<ClosureMark> closures;
};

enum class OverviewView { kTopDown, kOblique };

/// Renders the overview: map coloured by height (MRPT scene, OSMesa); the reference as a wide light band under
/// the corrected trajectory, the odometry dashed on top, closures as dots at the revisited places, all drawn
/// anti-aliased on the projected frame (MRPT 2.5 ignores line widths); legend, and a scale bar with north
/// arrow (top-down) or axes glyph and grid spacing (oblique).
cv::Mat RenderOverview(const OverviewData& data, OverviewView view, const RenderConfig& config = {});

}  // namespace revisit
