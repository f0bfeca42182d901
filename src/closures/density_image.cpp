#include "closures/density_image.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/imgcodecs.hpp>

namespace revisit {
namespace {

double ChooseResolution(double extent, const DensityImageConfig& config) {
    double resolution = config.resolution;
    if (config.target_extent_pixels > 0) {
        resolution = std::clamp(extent / config.target_extent_pixels, config.min_resolution, config.max_resolution);
    }
    return std::max(resolution, extent / std::max(1, config.max_image_side - 1));
}

}  // namespace

DensityImage ComputeDensityImage(const std::vector<Eigen::Vector3f>& points_in_level, const DensityImageConfig& config) {
    DensityImage result;
    result.resolution = config.resolution;
    if (points_in_level.empty()) {
        result.image = cv::Mat::zeros(1, 1, CV_8UC1);
        return result;
    }
    Eigen::Vector2f lo = points_in_level.front().head<2>(), hi = lo;
    for (const auto& p : points_in_level) {
        lo = lo.cwiseMin(p.head<2>());
        hi = hi.cwiseMax(p.head<2>());
    }
    const double resolution = ChooseResolution(double((hi - lo).maxCoeff()), config);
    const int cols = int(std::floor((hi.x() - lo.x()) / resolution)) + 1;
    const int rows = int(std::floor((hi.y() - lo.y()) / resolution)) + 1;
    result.resolution = resolution;
    result.origin = lo.cast<double>() + Eigen::Vector2d::Constant(0.5 * resolution);

    // Per cell: point count (density) or maximum height (elevation ablation).
    std::vector<float> cells(std::size_t(rows) * cols, config.elevation_instead ? -std::numeric_limits<float>::infinity() : 0.f);
    for (const auto& p : points_in_level) {
        const int u = std::min(cols - 1, int((p.x() - lo.x()) / resolution));
        const int v = std::min(rows - 1, int((p.y() - lo.y()) / resolution));
        float& cell = cells[std::size_t(v) * cols + u];
        cell = config.elevation_instead ? std::max(cell, p.z()) : cell + 1.f;
    }
    std::vector<float> lit;
    lit.reserve(cells.size());
    for (float c : cells) {
        if (config.elevation_instead ? std::isfinite(c) : c > 0.f) lit.push_back(c);
    }
    // METHOD.md section 3: (N - N_min) / (N_max - N_min) over the occupied cells.
    const float n_min = config.elevation_instead ? *std::min_element(lit.begin(), lit.end()) : 0.f;
    float n_max = *std::max_element(lit.begin(), lit.end());
    if (config.scaling == DensityScaling::kPercentile && !config.elevation_instead) {
        const auto k = std::size_t(std::clamp(config.scale_percentile, 0.0, 1.0) * double(lit.size() - 1));
        std::nth_element(lit.begin(), lit.begin() + k, lit.end());
        n_max = std::max(lit[k], n_min + 1.f);
    }
    const float range = std::max(n_max - n_min, 1e-6f);

    result.image = cv::Mat::zeros(rows, cols, CV_8UC1);
    for (int v = 0; v < rows; ++v) {
        auto* row = result.image.ptr<std::uint8_t>(v);
        for (int u = 0; u < cols; ++u) {
            const float c = cells[std::size_t(v) * cols + u];
            if (config.elevation_instead ? !std::isfinite(c) : c <= 0.f) continue;
            // Elevation: occupied cells start at 1 so the lowest occupied cell is not lost as empty.
            const float normalized = std::min(1.f, (c - n_min) / range);
            const float byte_value = config.elevation_instead ? 1.f + 254.f * normalized : 255.f * normalized;
            const bool below = config.threshold == DensityThreshold::kFractionOfMax
                                   ? normalized < config.min_density
                                   : byte_value < config.min_density;
            if (!below) row[u] = std::uint8_t(std::lround(byte_value));
        }
    }
    return result;
}

std::vector<std::uint8_t> EncodeDensityPng(const cv::Mat& image) {
    std::vector<std::uint8_t> png;
    cv::imencode(".png", image, png, {cv::IMWRITE_PNG_STRATEGY, cv::IMWRITE_PNG_STRATEGY_RLE});
    png.shrink_to_fit();
    return png;
}

}  // namespace revisit
