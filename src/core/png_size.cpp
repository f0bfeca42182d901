#include "core/png_size.hpp"

#include <cstring>
#include <fstream>
#include <string>

#include "core/error.hpp"

namespace revisit {
namespace {
constexpr std::size_t kHeaderBytes = 24;  // 8 signature + 4 length + 4 "IHDR" + 4 width + 4 height
constexpr unsigned char kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};

std::uint32_t BigEndian32(const std::uint8_t* p) {
    return (std::uint32_t(p[0]) << 24) | (std::uint32_t(p[1]) << 16) | (std::uint32_t(p[2]) << 8) | std::uint32_t(p[3]);
}
}  // namespace

PngSize ReadPngSize(const std::uint8_t* data, std::size_t size, const std::filesystem::path& file) {
    if (size < kHeaderBytes || std::memcmp(data, kSignature, sizeof(kSignature)) != 0 ||
        std::memcmp(data + 12, "IHDR", 4) != 0) {
        throw DatasetError(file, "not a PNG image (no PNG signature and IHDR header)");
    }
    return PngSize{BigEndian32(data + 16), BigEndian32(data + 20)};
}

PngSize ReadPngSize(const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    if (!in) throw DatasetError(file, "cannot open for reading");
    std::uint8_t header[kHeaderBytes] = {};
    in.read(reinterpret_cast<char*>(header), kHeaderBytes);
    return ReadPngSize(header, static_cast<std::size_t>(in.gcount()), file);
}

void CheckPngSize(const PngSize& png, int max_side, const std::filesystem::path& file) {
    // floor(extent / resolution) + 1 cells may round one past the configured side.
    const auto limit = static_cast<std::uint32_t>(max_side) + 1;
    if (png.width == 0 || png.height == 0 || png.width > limit || png.height > limit) {
        throw DatasetError(file, "image declares " + std::to_string(png.width) + " x " + std::to_string(png.height) +
                                     " pixels; density images are at most density.max_image_side = " +
                                     std::to_string(max_side) + " pixels per side");
    }
}

}  // namespace revisit
