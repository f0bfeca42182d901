#include "render/palette.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace revisit {

namespace {

/// `t` in [0, 1] (anything else clamped, NaN as 0) mapped linearly through three colour stops.
Rgb ThroughStops(const std::array<Rgb, 3>& stops, double t) {
    t = std::clamp(std::isfinite(t) ? t : 0.0, 0.0, 1.0);
    const double s = t * (stops.size() - 1);
    const auto i = std::min<std::size_t>(static_cast<std::size_t>(s), stops.size() - 2);
    const double f = s - static_cast<double>(i);
    const auto mix = [f](std::uint8_t a, std::uint8_t b) { return static_cast<std::uint8_t>(std::lround(a + f * (b - a))); };
    return {mix(stops[i].r, stops[i + 1].r), mix(stops[i].g, stops[i + 1].g), mix(stops[i].b, stops[i + 1].b)};
}

}  // namespace

Rgb HeightColor(double t) {
    // Three pastel stops.
    static constexpr std::array<Rgb, 3> kStops{Rgb{120, 150, 190}, Rgb{140, 175, 140}, Rgb{205, 170, 110}};
    return ThroughStops(kStops, t);
}

Rgb DensityColor(double t) {
    // Light blue to navy: empty-looking cells stay visible on white.
    static constexpr std::array<Rgb, 3> kStops{Rgb{160, 200, 240}, Rgb{60, 120, 200}, Rgb{10, 25, 95}};
    return ThroughStops(kStops, t);
}

}  // namespace revisit
