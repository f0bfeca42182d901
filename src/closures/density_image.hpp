#pragma once
/// Bird's-eye density images of levelled local maps (METHOD.md section 3; thesis section 4.2).
#include <Eigen/Core>
#include <cstdint>
#include <opencv2/core.hpp>
#include <vector>

namespace revisit {

/// How counts become 8-bit intensities.
enum class DensityScaling {
    kMinMax,      ///< paper: (N - N_min) / (N_max - N_min), scaled by the single densest cell
    kPercentile,  ///< beyond the paper: scale by a high percentile of lit cells and saturate (METHOD.md 5b)
};

/// What the 5% threshold is compared against.
enum class DensityThreshold {
    kFractionOfMax,  ///< paper text: cells below min_density of the maximum become 0
    kByteScale,      ///< paper-era code: min_density compared on the 0-255 scale (removes almost nothing)
};

struct DensityImageConfig {
    double resolution = 0.5;        ///< nu_res [m per pixel]
    double min_density = 0.05;      ///< cells below this become 0; semantics set by `threshold` [0..1]
    DensityThreshold threshold = DensityThreshold::kFractionOfMax;
    DensityScaling scaling = DensityScaling::kMinMax;
    double scale_percentile = 0.95; ///< kPercentile: this quantile of lit cells maps to 255 [0..1]
    bool elevation_instead = false; ///< ablation: maximum height per cell instead of the point count
    /// Beyond the paper: pick the resolution from the map's extent so that its longer side has about
    /// `target_extent_pixels`, clamped to [min_resolution, max_resolution]. 0 keeps `resolution`.
    int target_extent_pixels = 0;
    double min_resolution = 0.05;   ///< [m per pixel]
    double max_resolution = 0.5;    ///< [m per pixel]
    int max_image_side = 4000;      ///< [pixels] guard against huge images; the resolution grows beyond this
};

struct DensityImage {
    cv::Mat image;                                     ///< CV_8UC1, row = y, column = x
    Eigen::Vector2d origin = Eigen::Vector2d::Zero();  ///< [m] levelled-frame x, y of the centre of pixel (0, 0)
    double resolution = 0.5;                           ///< [m per pixel]

    /// Levelled-frame metric position of a pixel coordinate (column u, row v).
    Eigen::Vector2d ToMetric(double u, double v) const { return origin + resolution * Eigen::Vector2d(u, v); }
};

/// Projects points (already in the levelled frame) orthographically onto z = 0 and builds the image.
DensityImage ComputeDensityImage(const std::vector<Eigen::Vector3f>& points_in_level, const DensityImageConfig& config = {});

/// Lossless PNG of a density image for storage in memory and in the database. Run-length deflate:
/// density images are mostly empty, and RLE is both the smallest (about 30% below the default
/// strategy at any level on KITTI and simulated maps) and the fastest to encode.
std::vector<std::uint8_t> EncodeDensityPng(const cv::Mat& image);

}  // namespace revisit
