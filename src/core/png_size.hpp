#pragma once
/// Image sizes read from a PNG's IHDR chunk, so that a damaged or hostile header is refused before a
/// decoder allocates width x height pixels.
#include <cstddef>
#include <cstdint>
#include <filesystem>

namespace revisit {

struct PngSize {
    std::uint32_t width = 0;   ///< [pixels]
    std::uint32_t height = 0;  ///< [pixels]
};

/// The size declared by PNG bytes (signature and IHDR); throws DatasetError naming `file` when they
/// are not a PNG.
PngSize ReadPngSize(const std::uint8_t* data, std::size_t size, const std::filesystem::path& file);
PngSize ReadPngSize(const std::filesystem::path& file);

/// Throws DatasetError naming `file` unless both sides are in [1, max_side].
void CheckPngSize(const PngSize& png, int max_side, const std::filesystem::path& file);

}  // namespace revisit
