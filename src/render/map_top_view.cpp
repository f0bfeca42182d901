#include "render/map_top_view.hpp"

#include <algorithm>
#include <cmath>

#include "render/annotate.hpp"

#include <opencv2/imgproc.hpp>

namespace revisit {

cv::Mat RenderMapTopView(const std::vector<Eigen::Vector3f>& points, const MapTopViewConfig& config) {
    constexpr int kMargin = 40;  // [pixels] room for the scale bar
    if (points.empty()) return cv::Mat(2 * kMargin, 2 * kMargin, CV_8UC3, cv::Scalar(255, 255, 255));
    Eigen::Vector2f low = points.front().head<2>(), high = low;
    for (const auto& p : points) {
        low = low.cwiseMin(p.head<2>());
        high = high.cwiseMax(p.head<2>());
    }
    const double extent = std::max(high.x() - low.x(), high.y() - low.y());
    const double cell = std::max(config.min_pixel, extent / std::max(1, config.max_side));
    const int width = static_cast<int>((high.x() - low.x()) / cell) + 1 + 2 * kMargin;
    const int height = static_cast<int>((high.y() - low.y()) / cell) + 1 + 2 * kMargin;
    cv::Mat count(height, width, CV_16UC1, cv::Scalar(0));
    for (const auto& p : points) {
        const int col = kMargin + static_cast<int>((p.x() - low.x()) / cell);
        const int row = height - 1 - kMargin - static_cast<int>((p.y() - low.y()) / cell);
        auto& n = count.at<std::uint16_t>(row, col);
        if (n < 1000) ++n;
    }
    cv::Mat image(height, width, CV_8UC3, cv::Scalar(255, 255, 255));
    for (int row = 0; row < height; ++row)
        for (int col = 0; col < width; ++col) {
            const int n = count.at<std::uint16_t>(row, col);
            if (n == 0) continue;
            // Dark from the first point: a sparse map (a few points per cell) must still read on white.
            const auto grey = static_cast<unsigned char>(std::max(0, 110 - 30 * (n - 1)));
            image.at<cv::Vec3b>(row, col) = cv::Vec3b(grey, grey, grey);
        }
    // A sparse map (a walk's few points per cell over a large extent) would be dots on white: each point then
    // darkens its 3 x 3 neighbourhood (a grey-level erosion), which keeps walls one line, only wider.
    const double occupied = double(cv::countNonZero(count)) / double(count.total());
    if (occupied < 0.05) cv::erode(image, image, cv::Mat::ones(3, 3, CV_8U));
    DrawScaleBar(image, 1.0 / cell);
    return image;
}

}  // namespace revisit
