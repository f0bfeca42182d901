#include "render/png_encoding.hpp"

#include <png.h>

#include <algorithm>
#include <array>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>
#include <unordered_map>

namespace revisit {
namespace {

void AppendBytes(png_structp png, png_bytep data, png_size_t length) {
    auto* out = static_cast<std::vector<std::uint8_t>*>(png_get_io_ptr(png));
    out->insert(out->end(), data, data + length);
}

void FlushNothing(png_structp) {}

/// Smallest PNG bit depth that holds `colors` palette indices.
int PaletteBitDepth(std::size_t colors) { return colors <= 2 ? 1 : colors <= 4 ? 2 : colors <= 16 ? 4 : 8; }

/// One byte per pixel (grey level or palette index) as PNG; `palette` empty for grey.
std::vector<std::uint8_t> WriteSamples(const cv::Mat& samples, const std::vector<png_color>& palette, int level) {
    std::vector<std::uint8_t> out;
    std::vector<png_bytep> rows(samples.rows);
    for (int r = 0; r < samples.rows; ++r) rows[r] = const_cast<png_bytep>(samples.ptr<std::uint8_t>(r));
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
    if (!png) throw std::runtime_error("PNG: cannot create the encoder");
    png_infop info = png_create_info_struct(png);
    if (!info || setjmp(png_jmpbuf(png))) {
        png_destroy_write_struct(&png, &info);
        throw std::runtime_error("PNG: encoding failed");
    }
    png_set_write_fn(png, &out, AppendBytes, FlushNothing);
    png_set_compression_level(png, level);
    if (palette.empty()) {
        png_set_IHDR(png, info, samples.cols, samples.rows, 8, PNG_COLOR_TYPE_GRAY, PNG_INTERLACE_NONE,
                     PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    } else {
        // Indexed pictures compress best unfiltered (libpng's own advice for palette images).
        png_set_filter(png, PNG_FILTER_TYPE_BASE, PNG_FILTER_NONE);
        png_set_IHDR(png, info, samples.cols, samples.rows, PaletteBitDepth(palette.size()), PNG_COLOR_TYPE_PALETTE,
                     PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
        png_set_PLTE(png, info, palette.data(), static_cast<int>(palette.size()));
    }
    png_write_info(png, info);
    png_set_packing(png);  // one byte per index in, packed to the bit depth out
    png_write_image(png, rows.data());
    png_write_end(png, info);
    png_destroy_write_struct(&png, &info);
    return out;
}

std::uint32_t Key(const cv::Vec3b& bgr) { return (std::uint32_t(bgr[2]) << 16) | (std::uint32_t(bgr[1]) << 8) | bgr[0]; }

png_color Color(std::uint32_t key) {
    return {static_cast<png_byte>(key >> 16), static_cast<png_byte>((key >> 8) & 255), static_cast<png_byte>(key & 255)};
}

/// The image's exact palette and indices, when it has at most `max_colors` colours (first seen, first listed).
bool ExactPalette(const cv::Mat& bgr, int max_colors, std::vector<png_color>* palette, cv::Mat* indices) {
    std::unordered_map<std::uint32_t, std::uint8_t> index_of;
    *indices = cv::Mat(bgr.size(), CV_8UC1);
    for (int r = 0; r < bgr.rows; ++r) {
        const auto* in = bgr.ptr<cv::Vec3b>(r);
        auto* out = indices->ptr<std::uint8_t>(r);
        for (int c = 0; c < bgr.cols; ++c) {
            const std::uint32_t key = Key(in[c]);
            auto it = index_of.find(key);
            if (it == index_of.end()) {
                if (static_cast<int>(index_of.size()) == max_colors) return false;
                it = index_of.emplace(key, static_cast<std::uint8_t>(index_of.size())).first;
                palette->push_back(Color(key));
            }
            out[c] = it->second;
        }
    }
    return true;
}

/// Popularity quantization on a 5-bit-per-channel histogram: the most frequent bins (ties: the lower bin)
/// become the palette, each at the mean colour of its pixels; every bin maps to its nearest entry.
void QuantizedPalette(const cv::Mat& bgr, int max_colors, std::vector<png_color>* palette, cv::Mat* indices) {
    constexpr int kBins = 1 << 15;
    const auto bin = [](const cv::Vec3b& p) { return ((p[2] >> 3) << 10) | ((p[1] >> 3) << 5) | (p[0] >> 3); };
    std::vector<std::uint64_t> count(kBins, 0);
    std::vector<std::array<std::uint64_t, 3>> sum(kBins, {0, 0, 0});
    for (int r = 0; r < bgr.rows; ++r) {
        const auto* in = bgr.ptr<cv::Vec3b>(r);
        for (int c = 0; c < bgr.cols; ++c) {
            const int b = bin(in[c]);
            ++count[b];
            sum[b][0] += in[c][2], sum[b][1] += in[c][1], sum[b][2] += in[c][0];
        }
    }
    std::vector<int> order(kBins);
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return count[a] > count[b]; });
    std::vector<std::array<int, 3>> entries;
    for (int i = 0; i < kBins && static_cast<int>(entries.size()) < max_colors && count[order[i]] > 0; ++i) {
        const int b = order[i];
        const auto n = count[b];
        entries.push_back({int((sum[b][0] + n / 2) / n), int((sum[b][1] + n / 2) / n), int((sum[b][2] + n / 2) / n)});
    }
    std::vector<std::uint8_t> entry_of_bin(kBins, 0);
    for (int b = 0; b < kBins; ++b) {
        if (count[b] == 0) continue;
        const std::array<int, 3> centre{(b >> 10) * 8 + 4, ((b >> 5) & 31) * 8 + 4, (b & 31) * 8 + 4};
        int best = 0, best_distance = std::numeric_limits<int>::max();
        for (std::size_t e = 0; e < entries.size(); ++e) {
            int d = 0;
            for (int k = 0; k < 3; ++k) d += (entries[e][k] - centre[k]) * (entries[e][k] - centre[k]);
            if (d < best_distance) best_distance = d, best = static_cast<int>(e);
        }
        entry_of_bin[b] = static_cast<std::uint8_t>(best);
    }
    for (const auto& e : entries)
        palette->push_back({static_cast<png_byte>(e[0]), static_cast<png_byte>(e[1]), static_cast<png_byte>(e[2])});
    *indices = cv::Mat(bgr.size(), CV_8UC1);
    for (int r = 0; r < bgr.rows; ++r) {
        const auto* in = bgr.ptr<cv::Vec3b>(r);
        auto* out = indices->ptr<std::uint8_t>(r);
        for (int c = 0; c < bgr.cols; ++c) out[c] = entry_of_bin[bin(in[c])];
    }
}

bool IsGrey(const cv::Mat& bgr) {
    for (int r = 0; r < bgr.rows; ++r) {
        const auto* in = bgr.ptr<cv::Vec3b>(r);
        for (int c = 0; c < bgr.cols; ++c)
            if (in[c][0] != in[c][1] || in[c][1] != in[c][2]) return false;
    }
    return true;
}

}  // namespace

std::vector<std::uint8_t> EncodePng(const cv::Mat& image, const PngEncodingConfig& config) {
    if (image.empty() || image.depth() != CV_8U || (image.channels() != 1 && image.channels() != 3))
        throw std::runtime_error("PNG: expected an 8-bit grey or BGR image, got " + std::to_string(image.channels()) +
                                 " channels of depth " + std::to_string(image.depth()));
    const int level = std::clamp(config.compression_level, 0, 9);
    if (image.channels() == 1) return WriteSamples(image, {}, level);
    if (IsGrey(image)) {
        cv::Mat grey;
        cv::extractChannel(image, grey, 0);
        return WriteSamples(grey, {}, level);
    }
    const int max_colors = std::clamp(config.max_colors, 2, 256);
    std::vector<png_color> palette;
    cv::Mat indices;
    if (!ExactPalette(image, max_colors, &palette, &indices)) {
        palette.clear();
        QuantizedPalette(image, max_colors, &palette, &indices);
    }
    return WriteSamples(indices, palette, level);
}

}  // namespace revisit
