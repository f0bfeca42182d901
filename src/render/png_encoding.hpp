#pragma once
/// PNG files as small as a picture allows, through libpng: 8-bit grey when every pixel is grey, else indexed
/// colour (a palette of at most 256 entries). OpenCV writes 24-bit RGB, three to ten times larger for the
/// report's pictures, whose colours are few (white paper, a palette of line colours, a colour map).
#include <opencv2/core.hpp>

#include <cstdint>
#include <vector>

namespace revisit {

struct PngEncodingConfig {
    int compression_level = 9;  ///< zlib level [0..9]
    int max_colors = 256;       ///< palette size [2..256]; pictures with more colours are quantized
};

/// Encodes an 8-bit image (1 channel grey, or 3 channels BGR as OpenCV draws) as PNG bytes. Pictures with more
/// colours than the palette holds are quantized deterministically: the most frequent colours (5 bits per
/// channel) become the palette, and every pixel takes its nearest entry. Throws std::runtime_error on failure.
std::vector<std::uint8_t> EncodePng(const cv::Mat& image, const PngEncodingConfig& config = {});

}  // namespace revisit
