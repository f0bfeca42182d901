#pragma once
/// 2D pictures of density images with OpenCV: the two images of a pair side by side with their matches, one
/// image with its keypoints, and the overlay of a pair at a relative pose. All on white, north up (image row =
/// -y), density in one colour map (palette DensityColor), scale bars in a strip below the images.
#include "closures/closure.hpp"
#include "closures/density_image.hpp"

#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace revisit {

struct DensityPictureConfig {
    int panel_side = 620;          ///< [pixels] longer side of the larger image of a pair; both share its scale
    int overlay_side = 640;        ///< [pixels] longer side of an overlay (before and after side by side on a page)
    int match_thickness = 2;       ///< [pixels] inlier lines
    double outlier_opacity = 0.2;  ///< outlier lines are blended this faint over the images [0..1]; 0 leaves them out
};

/// Query (left) and reference (right) density images at the same scale, their ORB keypoints, the inliers of
/// `closure` in green over faint red outliers, a legend and one scale bar below. A closure without matches
/// draws the two images and keypoints only.
cv::Mat DrawDensityMatches(const DensityImage& query, const DensityImage& ref, const Closure& closure,
                           const DensityPictureConfig& config = {});

/// One density image with its ORB keypoints, a title, legend, scale bar and north arrow (the per-map page).
cv::Mat DrawDensityKeypoints(const DensityImage& image, const std::vector<Eigen::Vector2f>& keypoints,
                             const std::string& title, const DensityPictureConfig& config = {});

/// How well two density images agree at a pose: occupied cells of the query image, and those of them with
/// reference structure in the same cell.
struct OverlayAgreement {
    int query_cells = 0;
    int shared_cells = 0;
    double Fraction() const { return query_cells > 0 ? double(shared_cells) / query_cells : 0.0; }
};

/// The reference image moved into the query image by the planar part (x, y, yaw) of T_query_ref, on white: query
/// structure red, reference blue, both in the same cell dark. Ground levelling is assumed near identity.
/// `agreement`, when given, receives the shared cells.
cv::Mat DrawDensityOverlay(const DensityImage& query, const DensityImage& ref, const Eigen::Matrix4d& T_query_ref,
                           const std::string& title, const DensityPictureConfig& config = {},
                           OverlayAgreement* agreement = nullptr);

}  // namespace revisit
