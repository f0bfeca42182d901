#pragma once
/// 3D view of two local maps in two colours, before or after alignment (issue 8, per-closure pictures).
#include "render/scene_common.hpp"

#include <Eigen/Geometry>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace revisit {

/// Smaller pictures than the overview: two per closure page.
RenderConfig MapPairRenderConfig();

/// Draws the query map (palette::kQueryMap) in its own frame and the reference map (palette::kRefMap) moved by
/// T_query_ref into it. Pass the odometry relative pose for "before", the closure's estimate for "after".
cv::Mat RenderMapPair(const std::vector<Eigen::Vector3f>& query_points, const std::vector<Eigen::Vector3f>& ref_points,
                      const Eigen::Isometry3d& T_query_ref, const std::string& title, bool oblique = true,
                      const RenderConfig& config = MapPairRenderConfig());

}  // namespace revisit
