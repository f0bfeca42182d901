#pragma once
/// One palette for every picture of the report, so a colour means the same thing on every page.
#include <opencv2/core.hpp>
#include <cstdint>

namespace revisit {

struct Rgb {
    std::uint8_t r = 0;
    std::uint8_t g = 0;
    std::uint8_t b = 0;

    cv::Scalar Bgr() const { return cv::Scalar(b, g, r); }  ///< OpenCV drawing order
};

namespace palette {
inline constexpr Rgb kBackground{255, 255, 255};
inline constexpr Rgb kText{20, 20, 20};
inline constexpr Rgb kOdometry{240, 120, 0};      ///< drifted odometry trajectory: orange
inline constexpr Rgb kCorrected{0, 90, 230};      ///< corrected trajectory: blue
inline constexpr Rgb kReference{150, 0, 170};     ///< ground truth: purple
inline constexpr Rgb kAccepted{0, 170, 60};       ///< accepted closure lines: green
inline constexpr Rgb kRejected{225, 30, 30};      ///< rejected closure lines: red, drawn faint
inline constexpr Rgb kQueryMap{230, 40, 40};      ///< the newer local map of a pair: red channel
inline constexpr Rgb kRefMap{0, 180, 230};        ///< the earlier local map of a pair: cyan (green+blue channels)
inline constexpr Rgb kInlier{0, 200, 0};          ///< RANSAC inlier matches
inline constexpr Rgb kOutlier{230, 0, 0};         ///< RANSAC outlier matches
inline constexpr Rgb kKeypoint{255, 200, 0};      ///< ORB keypoints: yellow
inline constexpr Rgb kReferenceBand{210, 180, 225};  ///< ground truth drawn as a wide light band under the others
inline constexpr Rgb kOverlayQuery{215, 25, 28};    ///< 2D overlays on white: query map only
inline constexpr Rgb kOverlayRef{30, 110, 225};     ///< reference map only
inline constexpr Rgb kOverlayBoth{20, 20, 20};      ///< both maps in the same cell: dark
}  // namespace palette

/// Height colour map for map points: pastel low-saturation ramp (blue-grey -> green-grey -> sand) so that the
/// saturated trajectory and closure colours stay readable on top of it. `t` in [0, 1].
Rgb HeightColor(double t);

/// Density colour map for 2D pictures on white: light blue for the faintest cells to dark navy for the densest,
/// so that structure stays visible and green / red match lines and yellow keypoints stand out. `t` in [0, 1].
Rgb DensityColor(double t);

}  // namespace revisit
