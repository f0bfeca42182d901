#pragma once
/// 2D pictures of density images with OpenCV: keypoints and matches side by side, and the overlay after alignment.
/// Images are shown north up (image row = -y), magnified by an integer factor, with a scale bar per panel.
#include "closures/closure.hpp"
#include "closures/density_image.hpp"

#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace revisit {

struct DensityPictureConfig {
    int min_panel_side = 480;  ///< [pixels] small images are magnified (integer factor) to at least this side
    int max_panel_side = 900;  ///< [pixels] and never beyond this
    int match_thickness = 1;   ///< [pixels]
};

/// Query (left) and reference (right) density images, ORB keypoints, the matches of `closure` (inliers green,
/// outliers red), legend and scale bars. A closure without matches draws the two images only.
cv::Mat DrawDensityMatches(const DensityImage& query, const DensityImage& ref, const Closure& closure,
                           const DensityPictureConfig& config = {});

/// One density image with its ORB keypoints, a title, legend, scale bar and north arrow (the per-map page).
cv::Mat DrawDensityKeypoints(const DensityImage& image, const std::vector<Eigen::Vector2f>& keypoints,
                             const std::string& title, const DensityPictureConfig& config = {});

/// The reference image moved into the query image by the planar part (x, y, yaw) of T_query_ref: query in the red
/// channel, reference in green and blue (cyan), overlap white. Ground levelling is assumed near identity.
cv::Mat DrawDensityOverlay(const DensityImage& query, const DensityImage& ref, const Eigen::Matrix4d& T_query_ref,
                           const std::string& title, const DensityPictureConfig& config = {});

}  // namespace revisit
