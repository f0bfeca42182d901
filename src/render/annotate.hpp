#pragma once
/// 2D annotations drawn with OpenCV on rendered frames: legends, scale bars, north arrow, thick lines.
/// Hershey fonts only, so the pictures are identical on every machine.
#include "render/palette.hpp"

#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace revisit {

struct LegendEntry {
    std::string label;
    Rgb color;
    bool line = true;  ///< a line sample; false: a filled square
};

/// A round length (1, 2 or 5 times a power of ten) close to `target_m` [m].
double NiceLength(double target_m);

/// Legend box in the top-left corner.
void DrawLegend(cv::Mat& image, const std::vector<LegendEntry>& entries, const std::string& title = "");

/// Scale bar in the bottom-left corner, `pixels_per_metre` along the image x axis; labelled in metres.
void DrawScaleBar(cv::Mat& image, double pixels_per_metre);

/// North (+y of the world) arrow in the top-right corner, `angle_rad` = image direction of +y measured from
/// the image's up direction, clockwise.
void DrawNorthArrow(cv::Mat& image, double angle_rad);

/// World axes glyph (x red, y green, z blue) at the bottom-right from the projected unit directions.
void DrawAxesGlyph(cv::Mat& image, const cv::Point2d& x_dir, const cv::Point2d& y_dir, const cv::Point2d& z_dir);

/// Text with a white halo, readable on any background.
void DrawLabel(cv::Mat& image, const std::string& text, cv::Point origin, double scale = 0.5, Rgb color = palette::kText);

/// Polylines with anti-aliasing, all in one colour; `opacity` < 1 blends them over the image.
using Polyline2d = std::vector<cv::Point2d>;
void DrawPolylines(cv::Mat& image, const std::vector<Polyline2d>& polylines, Rgb color, int thickness, double opacity = 1.0);

/// A polyline drawn dashed: `dash` pixels on, `gap` off, the pattern running on along the whole line.
void DrawDashedPolyline(cv::Mat& image, const Polyline2d& polyline, Rgb color, int thickness, double dash, double gap);

}  // namespace revisit
