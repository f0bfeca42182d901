#include "evaluation/azimuth_sector.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace revisit {

int ExactSector(float x, float y, int num_sectors) {
    constexpr float kDegPerRad = static_cast<float>(180.0 / M_PI);
    float azimuth_deg = std::atan2(y, x) * kDegPerRad;
    if (azimuth_deg < 0.0f) azimuth_deg += 360.0f;
    return ScanContextBin(azimuth_deg, 360.0f, num_sectors) - 1;
}

SectorOfAzimuth::SectorOfAzimuth(int num_sectors)
    : num_sectors_(num_sectors),
      sectors_per_radian_(static_cast<float>(num_sectors / (2.0 * M_PI))),
      margin_sectors_(static_cast<float>(kMarginDeg * num_sectors / 360.0)) {}

void SectorOfAzimuth::operator()(const std::vector<Eigen::Vector3f>& points, std::vector<int>& sectors) const {
    constexpr float kPi = static_cast<float>(M_PI);
    constexpr float kFinite = std::numeric_limits<float>::max();
    const float last = static_cast<float>(num_sectors_);
    sectors.resize(points.size());
    // No calls and no branches to mispredict (selects between computed values); -1 marks the points
    // the exact rule decides, in the loop after.
    for (std::size_t k = 0; k < points.size(); ++k) {
        const float x = points[k].x(), y = points[k].y();
        const float ax = std::abs(x), ay = std::abs(y);
        const bool steep = ay > ax;
        const float hi = steep ? ay : ax, lo = steep ? ax : ay;
        // atan on [0, 1] (Abramowitz & Stegun 4.4.47, |error| <= 1e-5 rad; 1.15e-5 with these rounded
        // coefficients), then the octant: a in [0, 2 pi] from the positive x axis, counter-clockwise.
        const float t = lo / hi, t2 = t * t;  // NaN at the origin: clamped and flagged below
        // Both sides of each choice are computed: selecting between values needs no branch.
        const float a0 = t * (0.9998660f + t2 * (-0.3302995f + t2 * (0.1801410f + t2 * (-0.0851330f + t2 * 0.0208351f))));
        const float complement = kPi / 2 - a0;
        const float a1 = steep ? complement : a0;
        const float mirrored1 = kPi - a1;
        const float a2 = x < 0.0f ? mirrored1 : a1;
        const float mirrored2 = 2 * kPi - a2;
        const float a = y < 0.0f ? mirrored2 : a2;
        // In sectors: boundaries at the integers. Clamped, so a non-finite point converts safely too.
        const float unclamped = a * sectors_per_radian_;
        const float position = unclamped > 0.0f ? (unclamped < last ? unclamped : last) : 0.0f;
        const float nearest = static_cast<float>(static_cast<int>(position + 0.5f));
        const float off_boundary = std::abs(position - nearest);
        // The origin, NaN and infinities go to the exact rule, whatever it gives there.
        const bool fast = (ax <= kFinite) & (ay <= kFinite) & (hi > 0.0f) & (off_boundary >= margin_sectors_);
        // Here margin_sectors_ < position < num_sectors - margin_sectors_.
        sectors[k] = fast ? static_cast<int>(position) : -1;
    }
    for (std::size_t k = 0; k < points.size(); ++k)
        if (sectors[k] < 0) sectors[k] = ExactSector(points[k].x(), points[k].y(), num_sectors_);
}

}  // namespace revisit
