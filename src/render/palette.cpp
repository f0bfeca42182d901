#include "render/palette.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace revisit {

Rgb HeightColor(double t) {
    // Three pastel stops; linear interpolation between them.
    static constexpr std::array<Rgb, 3> kStops{Rgb{120, 150, 190}, Rgb{140, 175, 140}, Rgb{205, 170, 110}};
    t = std::clamp(std::isfinite(t) ? t : 0.0, 0.0, 1.0);
    const double s = t * (kStops.size() - 1);
    const auto i = std::min<std::size_t>(static_cast<std::size_t>(s), kStops.size() - 2);
    const double f = s - static_cast<double>(i);
    const auto mix = [f](std::uint8_t a, std::uint8_t b) { return static_cast<std::uint8_t>(std::lround(a + f * (b - a))); };
    return {mix(kStops[i].r, kStops[i + 1].r), mix(kStops[i].g, kStops[i + 1].g), mix(kStops[i].b, kStops[i + 1].b)};
}

Rgb DensityColor(double t) {
    static constexpr std::array<Rgb, 3> kStops{Rgb{160, 200, 240}, Rgb{60, 120, 200}, Rgb{10, 25, 95}};
    t = std::clamp(std::isfinite(t) ? t : 0.0, 0.0, 1.0);
    const double s = t * (kStops.size() - 1);
    const auto i = std::min<std::size_t>(static_cast<std::size_t>(s), kStops.size() - 2);
    const double f = s - static_cast<double>(i);
    const auto mix = [f](std::uint8_t a, std::uint8_t b) { return static_cast<std::uint8_t>(std::lround(a + f * (b - a))); };
    return {mix(kStops[i].r, kStops[i + 1].r), mix(kStops[i].g, kStops[i + 1].g), mix(kStops[i].b, kStops[i + 1].b)};
}

}  // namespace revisit
