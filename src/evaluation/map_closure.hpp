#pragma once
/// A detected closure between two local maps, as the evaluation needs it (the pipeline adapts the
/// closure detector's output to this, so evaluation does not depend on the closures module).
#include <Eigen/Geometry>
#include <cstddef>

namespace revisit {

struct MapClosureForEval {
    std::size_t query_first_scan = 0;  ///< first scan of the query (later) map; its pose is the map frame
    std::size_t query_last_scan = 0;   ///< inclusive
    std::size_t ref_first_scan = 0;    ///< first scan of the reference (earlier) map; its pose is the map frame
    std::size_t ref_last_scan = 0;     ///< inclusive
    Eigen::Isometry3d T_query_ref = Eigen::Isometry3d::Identity();  ///< reference map frame -> query map frame
    double inliers = 0.0;              ///< RANSAC inliers: the score the sweep thresholds
};

}  // namespace revisit
