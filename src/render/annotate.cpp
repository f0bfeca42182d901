#include "render/annotate.hpp"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace revisit {
namespace {

constexpr int kFont = cv::FONT_HERSHEY_SIMPLEX;
constexpr int kShift = 4;  // sub-pixel bits for cv::line / cv::polylines
constexpr double kSubPixel = 1 << kShift;

cv::Point Fixed(const cv::Point2d& p) {
    return {static_cast<int>(std::lround(p.x * kSubPixel)), static_cast<int>(std::lround(p.y * kSubPixel))};
}

std::string FormatMetres(double length_m) {
    char text[32];
    if (length_m >= 1000.0) std::snprintf(text, sizeof(text), "%g km", length_m / 1000.0);
    else if (length_m >= 1.0) std::snprintf(text, sizeof(text), "%g m", length_m);
    else std::snprintf(text, sizeof(text), "%g cm", length_m * 100.0);
    return text;
}

}  // namespace

double NiceLength(double target_m) {
    if (!(target_m > 0.0) || !std::isfinite(target_m)) return 1.0;
    const double power = std::pow(10.0, std::floor(std::log10(target_m)));
    for (const double step : {5.0, 2.0, 1.0})
        if (step * power <= target_m) return step * power;
    return power;
}

void DrawLabel(cv::Mat& image, const std::string& text, cv::Point origin, double scale, Rgb color) {
    const int thickness = scale >= 0.6 ? 2 : 1;
    cv::putText(image, text, origin, kFont, scale, palette::kBackground.Bgr(), thickness + 3, cv::LINE_AA);
    cv::putText(image, text, origin, kFont, scale, color.Bgr(), thickness, cv::LINE_AA);
}

void DrawPolylines(cv::Mat& image, const std::vector<Polyline2d>& polylines, Rgb color, int thickness, double opacity) {
    if (polylines.empty()) return;
    cv::Mat layer = opacity < 1.0 ? image.clone() : image;
    for (const auto& polyline : polylines) {
        if (polyline.size() < 2) continue;
        std::vector<cv::Point> fixed;
        fixed.reserve(polyline.size());
        for (const auto& p : polyline) fixed.push_back(Fixed(p));
        cv::polylines(layer, fixed, false, color.Bgr(), thickness, cv::LINE_AA, kShift);
    }
    if (opacity < 1.0) cv::addWeighted(layer, opacity, image, 1.0 - opacity, 0.0, image);
}

void DrawDashedPolyline(cv::Mat& image, const Polyline2d& polyline, Rgb color, int thickness, double dash, double gap) {
    if (polyline.size() < 2 || !(dash > 0.0) || !(gap >= 0.0)) return;
    const double period = dash + gap;
    double phase = 0.0;  // [pixels] into the current period at the start of each segment
    for (std::size_t i = 1; i < polyline.size(); ++i) {
        const cv::Point2d a = polyline[i - 1], d = polyline[i] - a;
        const double length = std::hypot(d.x, d.y);
        double s = 0.0;
        while (s < length) {
            const double in_period = std::fmod(phase + s, period);
            const double step = std::min(length - s, in_period < dash ? dash - in_period : period - in_period);
            if (in_period < dash)
                cv::line(image, Fixed(a + d * (s / length)), Fixed(a + d * ((s + step) / length)), color.Bgr(), thickness,
                         cv::LINE_AA, kShift);
            s += std::max(step, 1e-6);
        }
        phase = std::fmod(phase + length, period);
    }
}

void DrawLegend(cv::Mat& image, const std::vector<LegendEntry>& entries, const std::string& title) {
    if (entries.empty()) return;
    const int row = 24;
    int width = 0;
    for (const auto& entry : entries) {
        int baseline = 0;
        width = std::max(width, cv::getTextSize(entry.label, kFont, 0.5, 1, &baseline).width);
    }
    width += 84;  // sample, gap and padding before the labels
    if (!title.empty()) {
        int baseline = 0;
        width = std::max(width, cv::getTextSize(title, kFont, 0.55, 1, &baseline).width + 24);
    }
    const int top = 10 + (title.empty() ? 0 : row);
    const cv::Rect box(10, 10, width, top - 10 + row * static_cast<int>(entries.size()) + 12);
    cv::Mat roi = image(box & cv::Rect(0, 0, image.cols, image.rows));
    cv::Mat white(roi.size(), roi.type(), palette::kBackground.Bgr());
    cv::addWeighted(white, 0.85, roi, 0.15, 0.0, roi);
    cv::rectangle(image, box, cv::Scalar(120, 120, 120), 1);
    if (!title.empty()) DrawLabel(image, title, {18, 30}, 0.55);
    for (std::size_t i = 0; i < entries.size(); ++i) {
        const int y = top + 16 + row * static_cast<int>(i);
        if (entries[i].line)
            cv::line(image, {20, y - 5}, {60, y - 5}, entries[i].color.Bgr(), 4, cv::LINE_AA);
        else
            cv::rectangle(image, cv::Rect(32, y - 12, 14, 14), entries[i].color.Bgr(), cv::FILLED);
        DrawLabel(image, entries[i].label, {70, y}, 0.5);
    }
}

void DrawScaleBar(cv::Mat& image, double pixels_per_metre) {
    if (!(pixels_per_metre > 0.0) || !std::isfinite(pixels_per_metre)) return;
    const double length_m = NiceLength(0.2 * image.cols / pixels_per_metre);
    const int length_px = static_cast<int>(std::lround(length_m * pixels_per_metre));
    const cv::Point left(20, image.rows - 25);
    const cv::Point right(left.x + length_px, left.y);
    cv::rectangle(image, cv::Rect(left.x - 8, left.y - 30, length_px + 16, 42), palette::kBackground.Bgr(), cv::FILLED);
    cv::line(image, left, right, palette::kText.Bgr(), 3);
    cv::line(image, left + cv::Point(0, -8), left + cv::Point(0, 6), palette::kText.Bgr(), 2);
    cv::line(image, right + cv::Point(0, -8), right + cv::Point(0, 6), palette::kText.Bgr(), 2);
    DrawLabel(image, FormatMetres(length_m), {left.x, left.y - 12}, 0.5);
}

void DrawNorthArrow(cv::Mat& image, double angle_rad) {
    const cv::Point2d centre(image.cols - 40.0, 50.0);
    const cv::Point2d up(std::sin(angle_rad), -std::cos(angle_rad));
    const cv::Point2d side(-up.y, up.x);
    const std::vector<cv::Point> head{Fixed(centre + 25.0 * up), Fixed(centre - 18.0 * up + 12.0 * side),
                                      Fixed(centre - 8.0 * up), Fixed(centre - 18.0 * up - 12.0 * side)};
    cv::fillConvexPoly(image, head, palette::kText.Bgr(), cv::LINE_AA, kShift);
    const cv::Point2d label = centre - 38.0 * up;
    DrawLabel(image, "N", {static_cast<int>(label.x) - 7, static_cast<int>(label.y) + 7}, 0.6);
}

void DrawAxesGlyph(cv::Mat& image, const cv::Point2d& x_dir, const cv::Point2d& y_dir, const cv::Point2d& z_dir) {
    const cv::Point2d origin(image.cols - 70.0, image.rows - 50.0);
    const struct { cv::Point2d dir; Rgb color; const char* name; } axes[] = {
        {x_dir, {220, 0, 0}, "x"}, {y_dir, {0, 160, 0}, "y"}, {z_dir, {0, 0, 220}, "z"}};
    for (const auto& axis : axes) {
        const double norm = std::hypot(axis.dir.x, axis.dir.y);
        if (norm < 1e-6) continue;
        const cv::Point2d tip = origin + axis.dir * (35.0 / norm);
        cv::arrowedLine(image, Fixed(origin), Fixed(tip), axis.color.Bgr(), 2, cv::LINE_AA, kShift, 0.25);
        const cv::Point2d text = origin + axis.dir * (48.0 / norm);
        DrawLabel(image, axis.name, {static_cast<int>(text.x) - 4, static_cast<int>(text.y) + 5}, 0.5, axis.color);
    }
}

}  // namespace revisit
