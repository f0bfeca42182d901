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

constexpr int kHeader = 96;  // [pixels] titles, legend row and north arrow above the images
constexpr int kFooter = 64;  // [pixels] scale bar below the images
constexpr int kMinWidth = 640;  // [pixels] room for the legend row
const cv::Scalar kFrame(200, 200, 200);

/// Density image north up, min-max scaled densities boosted (mostly faint otherwise; saturating).
cv::Mat Boosted(const cv::Mat& density) {
    cv::Mat flipped;
    cv::flip(density, flipped, 0);
    flipped.convertTo(flipped, CV_8U, 3.0);
    return flipped;
}

/// Resized to `size`: nearest neighbour when magnifying (crisp cells), area average when shrinking.
cv::Mat Resized(const cv::Mat& image, cv::Size size) {
    size.width = std::max(1, size.width);
    size.height = std::max(1, size.height);
    cv::Mat out;
    const bool magnify = size.width >= image.cols;
    cv::resize(image, out, size, 0, 0, magnify ? cv::INTER_NEAREST : cv::INTER_AREA);
    return out;
}

/// Empty cells white, occupied ones through DensityColor.
cv::Mat Colorized(const cv::Mat& boosted) {
    cv::Mat lut(1, 256, CV_8UC3);
    lut.at<cv::Vec3b>(0) = cv::Vec3b(255, 255, 255);
    for (int v = 1; v < 256; ++v) {
        const Rgb c = DensityColor(std::sqrt(v / 255.0));  // most cells are faint: spread them over the ramp
        lut.at<cv::Vec3b>(v) = cv::Vec3b(c.b, c.g, c.r);
    }
    cv::Mat bgr, out;
    cv::cvtColor(boosted, bgr, cv::COLOR_GRAY2BGR);
    cv::LUT(bgr, lut, out);
    return out;
}

cv::Size ScaledSize(const DensityImage& d, double pixels_per_metre) {
    const double f = pixels_per_metre * d.resolution;
    return {int(std::lround(d.image.cols * f)), int(std::lround(d.image.rows * f))};
}

double LongerSide(const DensityImage& d) { return std::max(d.image.cols, d.image.rows) * d.resolution; }

/// Display position of a density-image pixel coordinate (column u, row v), `f` display pixels per image pixel.
cv::Point2d Display(const Eigen::Vector2f& uv, int rows, double f) { return {f * (uv.x() + 0.5), f * (rows - uv.y() - 0.5)}; }

cv::Point Round(const cv::Point2d& p) { return {static_cast<int>(std::lround(p.x)), static_cast<int>(std::lround(p.y))}; }

/// Legend entries in one row from `origin` (text baseline).
void DrawLegendRow(cv::Mat& canvas, const std::vector<LegendEntry>& entries, cv::Point origin) {
    int x = origin.x;
    for (const auto& entry : entries) {
        if (entry.line) cv::line(canvas, {x, origin.y - 5}, {x + 26, origin.y - 5}, entry.color.Bgr(), 3, cv::LINE_AA);
        else cv::rectangle(canvas, cv::Rect(x + 6, origin.y - 13, 14, 14), entry.color.Bgr(), cv::FILLED);
        DrawLabel(canvas, entry.label, {x + 34, origin.y}, 0.5);
        int baseline = 0;
        x += 34 + cv::getTextSize(entry.label, cv::FONT_HERSHEY_SIMPLEX, 0.5, 1, &baseline).width + 26;
    }
}

/// White canvas with room for the header and the footer around `panels` pixels.
cv::Mat Canvas(cv::Size panels) {
    return cv::Mat(kHeader + panels.height + kFooter, std::max(panels.width, kMinWidth), CV_8UC3, palette::kBackground.Bgr());
}

/// The scale bar in the footer strip below a panel of `panel_width` pixels starting at `x`, with a note beside it.
void DrawFooter(cv::Mat& canvas, int x, int panel_width, double pixels_per_metre, const std::string& note) {
    cv::Mat footer = canvas(cv::Rect(x, canvas.rows - kFooter, std::max(panel_width, 200), kFooter) &
                            cv::Rect(0, 0, canvas.cols, canvas.rows));
    DrawScaleBar(footer, pixels_per_metre);
    if (!note.empty()) {
        const double bar_px = NiceLength(0.2 * footer.cols / pixels_per_metre) * pixels_per_metre;
        DrawLabel(canvas, note, {x + 20 + int(bar_px) + 40, canvas.rows - 22}, 0.45, {90, 90, 90});
    }
}

}  // namespace

cv::Mat DrawDensityMatches(const DensityImage& query, const DensityImage& ref, const Closure& closure,
                           const DensityPictureConfig& config) {
    const double ppm = config.panel_side / std::max({LongerSide(query), LongerSide(ref), 1e-6});
    const cv::Mat left = Colorized(Resized(Boosted(query.image), ScaledSize(query, ppm)));
    const cv::Mat right = Colorized(Resized(Boosted(ref.image), ScaledSize(ref, ppm)));
    const int gap = 28;
    cv::Mat canvas = Canvas({left.cols + gap + right.cols, std::max(left.rows, right.rows)});
    const cv::Rect rect_q(0, kHeader, left.cols, left.rows), rect_r(left.cols + gap, kHeader, right.cols, right.rows);
    left.copyTo(canvas(rect_q));
    right.copyTo(canvas(rect_r));
    cv::rectangle(canvas, rect_q, kFrame, 1);
    cv::rectangle(canvas, rect_r, kFrame, 1);

    const double f_q = ppm * query.resolution, f_r = ppm * ref.resolution;
    const cv::Point2d offset_q(rect_q.x, rect_q.y), offset_r(rect_r.x, rect_r.y);
    const auto key_q = [&](int i) { return offset_q + Display(closure.query_keypoints[i], query.image.rows, f_q); };
    const auto key_r = [&](int i) { return offset_r + Display(closure.ref_keypoints[i], ref.image.rows, f_r); };
    for (std::size_t i = 0; i < closure.query_keypoints.size(); ++i)
        cv::circle(canvas, Round(key_q(int(i))), 2, palette::kKeypoint.Bgr(), 1, cv::LINE_AA);
    for (std::size_t i = 0; i < closure.ref_keypoints.size(); ++i)
        cv::circle(canvas, Round(key_r(int(i))), 2, palette::kKeypoint.Bgr(), 1, cv::LINE_AA);

    std::vector<std::pair<cv::Point, cv::Point>> inlier_lines, outlier_lines;
    for (std::size_t m = 0; m < closure.matches.size(); ++m) {
        const auto& match = closure.matches[m];
        if (match.query_keypoint < 0 || match.ref_keypoint < 0 || match.query_keypoint >= int(closure.query_keypoints.size()) ||
            match.ref_keypoint >= int(closure.ref_keypoints.size()))
            continue;
        const bool inlier = m < closure.inlier_mask.size() && closure.inlier_mask[m] != 0;
        (inlier ? inlier_lines : outlier_lines).emplace_back(Round(key_q(match.query_keypoint)), Round(key_r(match.ref_keypoint)));
    }
    // Outliers faint and underneath: the inliers are what the reader checks.
    if (config.outlier_opacity > 0.0 && !outlier_lines.empty()) {
        cv::Mat layer = canvas.clone();
        for (const auto& [a, b] : outlier_lines) cv::line(layer, a, b, palette::kOutlier.Bgr(), 1, cv::LINE_AA);
        cv::addWeighted(layer, config.outlier_opacity, canvas, 1.0 - config.outlier_opacity, 0.0, canvas);
    }
    for (const auto& [a, b] : inlier_lines) {
        cv::line(canvas, a, b, palette::kInlier.Bgr(), config.match_thickness, cv::LINE_AA);
        cv::circle(canvas, a, 3, palette::kInlier.Bgr(), cv::FILLED, cv::LINE_AA);
        cv::circle(canvas, b, 3, palette::kInlier.Bgr(), cv::FILLED, cv::LINE_AA);
    }

    char text[160];
    std::snprintf(text, sizeof(text), "query map %d (scans %zu-%zu)", closure.query_id, closure.query_scans.first,
                  closure.query_scans.last);
    DrawLabel(canvas, text, {rect_q.x + 4, 26}, 0.55);
    std::snprintf(text, sizeof(text), "reference map %d (scans %zu-%zu)", closure.ref_id, closure.ref_scans.first,
                  closure.ref_scans.last);
    DrawLabel(canvas, text, {rect_r.x + 4, 26}, 0.55);
    std::vector<LegendEntry> legend;
    if (!closure.matches.empty()) {
        legend.push_back({"inliers (" + std::to_string(inlier_lines.size()) + ")", palette::kInlier});
        legend.push_back({"outliers (" + std::to_string(outlier_lines.size()) +
                              (config.outlier_opacity > 0.0 ? ", faint)" : ", not drawn)"),
                          palette::kOutlier});
    }
    legend.push_back({"ORB keypoints", palette::kKeypoint, false});
    legend.push_back({"density: low", DensityColor(0.0), false});
    legend.push_back({"high", DensityColor(1.0), false});
    DrawLegendRow(canvas, legend, {10, 62});
    DrawNorthArrow(canvas, 0.0);
    DrawFooter(canvas, 0, left.cols, ppm, "both images at the same scale");
    return canvas;
}

cv::Mat DrawDensityKeypoints(const DensityImage& image, const std::vector<Eigen::Vector2f>& keypoints,
                             const std::string& title, const DensityPictureConfig& config) {
    const double ppm = config.panel_side / std::max(LongerSide(image), 1e-6);
    const cv::Mat panel = Colorized(Resized(Boosted(image.image), ScaledSize(image, ppm)));
    cv::Mat canvas = Canvas(panel.size());
    const cv::Rect rect(0, kHeader, panel.cols, panel.rows);
    panel.copyTo(canvas(rect));
    cv::rectangle(canvas, rect, kFrame, 1);
    const double f = ppm * image.resolution;
    const cv::Point2d offset(rect.x, rect.y);
    for (const auto& keypoint : keypoints)
        cv::circle(canvas, Round(offset + Display(keypoint, image.image.rows, f)), 3, palette::kKeypoint.Bgr(), 1, cv::LINE_AA);
    DrawLabel(canvas, title, {4, 26}, 0.55);
    DrawLegendRow(canvas, {{"ORB keypoints (" + std::to_string(keypoints.size()) + ")", palette::kKeypoint, false},
                           {"density: low", DensityColor(0.0), false}, {"high", DensityColor(1.0), false}},
                  {10, 62});
    DrawNorthArrow(canvas, 0.0);
    DrawFooter(canvas, 0, panel.cols, ppm, "");
    return canvas;
}

cv::Mat DrawDensityOverlay(const DensityImage& query, const DensityImage& ref, const Eigen::Matrix4d& T_query_ref,
                           const std::string& title, const DensityPictureConfig& config, OverlayAgreement* agreement) {
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
    const cv::Size size(std::max(1, std::min(limit, int(std::ceil(hi.x() - lo.x())))),
                        std::max(1, std::min(limit, int(std::ceil(hi.y() - lo.y())))));
    Eigen::Matrix3d shift = Eigen::Matrix3d::Identity();
    shift.topRightCorner<2, 1>() = -lo;
    ref_to_query = shift * ref_to_query;
    const auto affine = [](const Eigen::Matrix3d& M) {
        return cv::Mat((cv::Mat_<double>(2, 3) << M(0, 0), M(0, 1), M(0, 2), M(1, 0), M(1, 1), M(1, 2)));
    };
    cv::Mat query_layer, ref_layer;
    cv::warpAffine(query.image, query_layer, affine(shift), size, cv::INTER_NEAREST, cv::BORDER_CONSTANT, 0);
    cv::warpAffine(ref.image, ref_layer, affine(ref_to_query), size, cv::INTER_NEAREST, cv::BORDER_CONSTANT, 0);
    query_layer = Boosted(query_layer);
    ref_layer = Boosted(ref_layer);
    if (agreement) {
        agreement->query_cells = cv::countNonZero(query_layer);
        cv::Mat both;
        cv::bitwise_and(query_layer > 0, ref_layer > 0, both);
        agreement->shared_cells = cv::countNonZero(both);
    }
    const double scale = double(config.overlay_side) / std::max(size.width, size.height);
    const cv::Size shown(int(std::lround(size.width * scale)), int(std::lround(size.height * scale)));
    query_layer = Resized(query_layer, shown);
    ref_layer = Resized(ref_layer, shown);

    // On white: a cell's colour says whose structure it holds; fainter structure lighter (8 steps).
    cv::Mat merged(query_layer.size(), CV_8UC3, palette::kBackground.Bgr());
    const auto tint = [](Rgb color, int value) {
        const double a = 0.45 + 0.55 * (std::min(value, 255) / 32) / 7.0;
        const auto mix = [a](int c) { return static_cast<std::uint8_t>(std::lround(255 - a * (255 - c))); };
        return cv::Vec3b(mix(color.b), mix(color.g), mix(color.r));
    };
    for (int r = 0; r < merged.rows; ++r) {
        const auto* q = query_layer.ptr<std::uint8_t>(r);
        const auto* f = ref_layer.ptr<std::uint8_t>(r);
        auto* out = merged.ptr<cv::Vec3b>(r);
        for (int c = 0; c < merged.cols; ++c) {
            if (q[c] > 0 && f[c] > 0) out[c] = tint(palette::kOverlayBoth, 255);
            else if (q[c] > 0) out[c] = tint(palette::kOverlayQuery, q[c]);
            else if (f[c] > 0) out[c] = tint(palette::kOverlayRef, f[c]);
        }
    }

    cv::Mat canvas = Canvas(merged.size());
    const cv::Rect rect(0, kHeader, merged.cols, merged.rows);
    merged.copyTo(canvas(rect));
    cv::rectangle(canvas, rect, kFrame, 1);
    DrawLabel(canvas, title, {4, 26}, 0.6);
    DrawLegendRow(canvas, {{"query map", palette::kOverlayQuery, false}, {"reference map", palette::kOverlayRef, false},
                           {"both (agree)", palette::kOverlayBoth, false}},
                  {10, 62});
    DrawNorthArrow(canvas, 0.0);
    DrawFooter(canvas, 0, merged.cols, scale / query.resolution, "");
    return canvas;
}

}  // namespace revisit
