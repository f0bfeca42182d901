#pragma once
/// The corrected map alone, seen from above, one pixel per cell: the picture that shows whether walls
/// are single or doubled after the closures (the overview draws trajectories and closures over it).
#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <vector>

namespace revisit {

struct MapTopViewConfig {
    double min_pixel = 0.05;  ///< [m] finest cell (a 2D laser's map voxel)
    int max_side = 1270;      ///< [pixels] longer side at most, margins aside (the report's page width); the cell grows for larger maps
};

/// Top view of `points` (x east, y north up): white where no point falls, grey for one point, darker
/// for more; a scale bar. Cell = max(min_pixel, longer extent / max_side). An empty map gives a
/// small white image.
cv::Mat RenderMapTopView(const std::vector<Eigen::Vector3f>& points, const MapTopViewConfig& config = {});

}  // namespace revisit
