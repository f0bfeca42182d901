#include "render/density_pictures.hpp"

#include "render/annotate.hpp"
#include "render/palette.hpp"

#include <Eigen/Geometry>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

namespace revisit {
namespace {

int Magnification(int rows, int cols, const DensityPictureConfig& config) {
    const int side = std::max({rows, cols, 1});
    return std::clamp(config.min_panel_side / side, 1, std::max(1, config.max_panel_side / side));
}

/// Density image shown north up and magnified, as BGR (white background, dark structure: readable when printed).
cv::Mat Panel(const cv::Mat& density, int scale) {
    cv::Mat flipped, grey, bgr;
    cv::flip(density, flipped, 0);
    flipped.convertTo(flipped, CV_8U, 3.0);  // min-max scaled densities are mostly faint: boost (saturating)
    cv::bitwise_not(flipped, grey);
    cv::resize(grey, grey, cv::Size(), scale, scale, cv::INTER_NEAREST);
    cv::cvtColor(grey, bgr, cv::COLOR_GRAY2BGR);
    return bgr;
}

/// Display position of a density-image pixel coordinate (column u, row v) in a north-up panel.
cv::Point2d Display(const Eigen::Vector2f& uv, int rows, int scale) {
    return {scale * (uv.x() + 0.5), scale * (rows - uv.y() - 0.5)};
}

cv::Point Round(const cv::Point2d& p) { return {static_cast<int>(std::lround(p.x)), static_cast<int>(std::lround(p.y))}; }

}  // namespace

cv::Mat DrawDensityMatches(const DensityImage& query, const DensityImage& ref, const Closure& closure,
                           const DensityPictureConfig& config) {
    const int scale_q = Magnification(query.image.rows, query.image.cols, config);
    const int scale_r = Magnification(ref.image.rows, ref.image.cols, config);
    const cv::Mat left = Panel(query.image, scale_q);
    const cv::Mat right = Panel(ref.image, scale_r);
    const int header = 150, gap = 20;
    cv::Mat canvas(std::max(left.rows, right.rows) + header, left.cols + gap + right.cols, CV_8UC3,
                   palette::kBackground.Bgr());
    left.copyTo(canvas(cv::Rect(0, header, left.cols, left.rows)));
    right.copyTo(canvas(cv::Rect(left.cols + gap, header, right.cols, right.rows)));
    const cv::Point2d offset_q(0, header), offset_r(left.cols + gap, header);

    const auto key_q = [&](int i) { return offset_q + Display(closure.query_keypoints[i], query.image.rows, scale_q); };
    const auto key_r = [&](int i) { return offset_r + Display(closure.ref_keypoints[i], ref.image.rows, scale_r); };
    for (std::size_t i = 0; i < closure.query_keypoints.size(); ++i)
        cv::circle(canvas, Round(key_q(int(i))), 3, palette::kKeypoint.Bgr(), 1, cv::LINE_AA);
    for (std::size_t i = 0; i < closure.ref_keypoints.size(); ++i)
        cv::circle(canvas, Round(key_r(int(i))), 3, palette::kKeypoint.Bgr(), 1, cv::LINE_AA);

    // Outliers first, so that the inliers stay visible on top.
    int inliers = 0;
    for (const bool draw_inliers : {false, true}) {
        for (std::size_t m = 0; m < closure.matches.size(); ++m) {
            const auto& match = closure.matches[m];
            const bool inlier = m < closure.inlier_mask.size() && closure.inlier_mask[m] != 0;
            if (inlier != draw_inliers) continue;
            if (match.query_keypoint < 0 || match.ref_keypoint < 0 ||
                match.query_keypoint >= int(closure.query_keypoints.size()) ||
                match.ref_keypoint >= int(closure.ref_keypoints.size()))
                continue;
            inliers += inlier;
            cv::line(canvas, Round(key_q(match.query_keypoint)), Round(key_r(match.ref_keypoint)),
                     (inlier ? palette::kInlier : palette::kOutlier).Bgr(), config.match_thickness, cv::LINE_AA);
        }
    }

    char text[160];
    std::snprintf(text, sizeof(text), "query map %d (scans %zu-%zu)", closure.query_id, closure.query_scans.first,
                  closure.query_scans.last);
    DrawLabel(canvas, text, {10, header - 12}, 0.55);
    std::snprintf(text, sizeof(text), "reference map %d (scans %zu-%zu)", closure.ref_id, closure.ref_scans.first,
                  closure.ref_scans.last);
    DrawLabel(canvas, text, {int(offset_r.x) + 10, header - 12}, 0.55);
    std::snprintf(text, sizeof(text), "inliers (%d)", inliers);
    const std::string inlier_text = text;
    std::snprintf(text, sizeof(text), "outliers (%d)", int(closure.matches.size()) - inliers);
    DrawLegend(canvas, {{inlier_text, palette::kInlier}, {text, palette::kOutlier}, {"ORB keypoints", palette::kKeypoint}});

    // One scale bar per panel: the two images may have different resolutions.
    cv::Mat panel_q = canvas(cv::Rect(0, header, left.cols, left.rows));
    cv::Mat panel_r = canvas(cv::Rect(left.cols + gap, header, right.cols, right.rows));
    DrawScaleBar(panel_q, scale_q / query.resolution);
    DrawScaleBar(panel_r, scale_r / ref.resolution);
    DrawNorthArrow(canvas, 0.0);
    return canvas;
}

cv::Mat DrawDensityKeypoints(const DensityImage& image, const std::vector<Eigen::Vector2f>& keypoints,
                             const std::string& title, const DensityPictureConfig& config) {
    const int scale = Magnification(image.image.rows, image.image.cols, config);
    const cv::Mat panel = Panel(image.image, scale);
    const int header = 110;
    cv::Mat canvas(panel.rows + header, std::max(panel.cols, 420), CV_8UC3, palette::kBackground.Bgr());
    panel.copyTo(canvas(cv::Rect(0, header, panel.cols, panel.rows)));
    const cv::Point2d offset(0, header);
    for (const auto& keypoint : keypoints)
        cv::circle(canvas, Round(offset + Display(keypoint, image.image.rows, scale)), 3, palette::kKeypoint.Bgr(), 1, cv::LINE_AA);
    DrawLabel(canvas, title, {10, header - 12}, 0.55);
    DrawLegend(canvas, {{"ORB keypoints (" + std::to_string(keypoints.size()) + ")", palette::kKeypoint}});
    cv::Mat panel_area = canvas(cv::Rect(0, header, panel.cols, panel.rows));
    DrawScaleBar(panel_area, scale / image.resolution);
    DrawNorthArrow(canvas, 0.0);
    return canvas;
}

cv::Mat DrawDensityOverlay(const DensityImage& query, const DensityImage& ref, const Eigen::Matrix4d& T_query_ref,
                           const std::string& title, const DensityPictureConfig& config) {
    // Pixel (u, v) -> levelled metres: A = [res 0 ox; 0 res oy]. Ref pixel -> query pixel: A_q^-1 * T_2d * A_r.
    const double yaw = std::atan2(T_query_ref(1, 0), T_query_ref(0, 0));
    Eigen::Matrix3d T_2d = Eigen::Matrix3d::Identity();
    T_2d.topLeftCorner<2, 2>() << std::cos(yaw), -std::sin(yaw), std::sin(yaw), std::cos(yaw);
    T_2d.topRightCorner<2, 1>() = T_query_ref.block<2, 1>(0, 3);
    const auto pixel_to_metric = [](const DensityImage& d) {
        Eigen::Matrix3d A = Eigen::Matrix3d::Identity();
        A(0, 0) = A(1, 1) = d.resolution;
        A.topRightCorner<2, 1>() = d.origin;
        return A;
    };
    Eigen::Matrix3d ref_to_query = pixel_to_metric(query).inverse() * T_2d * pixel_to_metric(ref);

    // Canvas: the union of the query image and the moved reference image, in query pixels.
    Eigen::Vector2d lo(0, 0), hi(query.image.cols, query.image.rows);
    for (const auto& corner : {Eigen::Vector2d(0, 0), Eigen::Vector2d(ref.image.cols, 0),
                               Eigen::Vector2d(0, ref.image.rows), Eigen::Vector2d(ref.image.cols, ref.image.rows)}) {
        const Eigen::Vector2d c = (ref_to_query * corner.homogeneous()).head<2>();
        lo = lo.cwiseMin(c);
        hi = hi.cwiseMax(c);
    }
    lo = lo.array().floor();
    const int limit = 4 * std::max({query.image.rows, query.image.cols, ref.image.rows, ref.image.cols});
    const cv::Size size(std::min(limit, int(std::ceil(hi.x() - lo.x()))), std::min(limit, int(std::ceil(hi.y() - lo.y()))));
    Eigen::Matrix3d shift = Eigen::Matrix3d::Identity();
    shift.topRightCorner<2, 1>() = -lo;
    ref_to_query = shift * ref_to_query;
    const auto affine = [](const Eigen::Matrix3d& M) {
        cv::Mat A = (cv::Mat_<double>(2, 3) << M(0, 0), M(0, 1), M(0, 2), M(1, 0), M(1, 1), M(1, 2));
        return A;
    };
    cv::Mat query_layer, ref_layer;
    cv::warpAffine(query.image, query_layer, affine(shift), size, cv::INTER_NEAREST, cv::BORDER_CONSTANT, 0);
    cv::warpAffine(ref.image, ref_layer, affine(ref_to_query), size, cv::INTER_LINEAR, cv::BORDER_CONSTANT, 0);
    // Two channels on black: query red, reference cyan; faint structure lifted so that it stays visible.
    const auto lift = [](cv::Mat& layer) { layer.convertTo(layer, CV_8U, 0.6, 0); cv::add(layer, 100, layer, layer > 0); };
    lift(query_layer);
    lift(ref_layer);
    cv::Mat merged;
    cv::merge(std::vector<cv::Mat>{ref_layer, ref_layer, query_layer}, merged);  // BGR
    cv::flip(merged, merged, 0);
    const int scale = Magnification(merged.rows, merged.cols, config);
    cv::resize(merged, merged, cv::Size(), scale, scale, cv::INTER_NEAREST);

    const int header = 130;
    cv::Mat canvas(merged.rows + header, std::max(merged.cols, 420), CV_8UC3, palette::kBackground.Bgr());
    merged.copyTo(canvas(cv::Rect(0, header, merged.cols, merged.rows)));
    DrawLegend(canvas, {{"query map", palette::kQueryMap, false}, {"reference map", palette::kRefMap, false}}, title + " (overlap white)");
    cv::Mat panel = canvas(cv::Rect(0, header, merged.cols, merged.rows));
    DrawScaleBar(panel, scale / query.resolution);
    DrawNorthArrow(canvas, 0.0);
    return canvas;
}

}  // namespace revisit
