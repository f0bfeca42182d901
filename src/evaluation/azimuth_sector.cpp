#include "evaluation/azimuth_sector.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

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

namespace {

// atan on [0, 1] (Abramowitz & Stegun 4.4.47, |error| <= 1e-5 rad; 1.15e-5 with these rounded
// coefficients), then the octant: a in [0, 2 pi] from the positive x axis, counter-clockwise.
constexpr float kAtan[] = {0.9998660f, -0.3302995f, 0.1801410f, -0.0851330f, 0.0208351f};
constexpr float kPi = static_cast<float>(M_PI);

/// One point's fast sector, or -1 where the exact rule must decide (SectorOfAzimuth's comment).
inline int FastSector(float x, float y, float sectors_per_radian, float last, float margin) {
    constexpr float kFinite = std::numeric_limits<float>::max();
    const float ax = std::abs(x), ay = std::abs(y);
    const bool steep = ay > ax;
    const float hi = steep ? ay : ax, lo = steep ? ax : ay;
    const float t = lo / hi, t2 = t * t;  // NaN at the origin: clamped and flagged below
    const float a0 = t * (kAtan[0] + t2 * (kAtan[1] + t2 * (kAtan[2] + t2 * (kAtan[3] + t2 * kAtan[4]))));
    const float a1 = steep ? kPi / 2 - a0 : a0;
    const float a2 = x < 0.0f ? kPi - a1 : a1;
    const float a = y < 0.0f ? 2 * kPi - a2 : a2;
    // In sectors: boundaries at the integers. Clamped, so a non-finite point converts safely too.
    const float unclamped = a * sectors_per_radian;
    const float position = unclamped > 0.0f ? (unclamped < last ? unclamped : last) : 0.0f;
    const float nearest = static_cast<float>(static_cast<int>(position + 0.5f));
    const bool fast = (ax <= kFinite) & (ay <= kFinite) & (hi > 0.0f) & (std::abs(position - nearest) >= margin);
    return fast ? static_cast<int>(position) : -1;
}

#if defined(__SSE2__)
/// FastSector of four points in SSE2 lanes: the same float operations in the same order (IEEE
/// single precision either way), so the same sectors; the scalar loop was not vectorized by the
/// compiler and cost a fifth of a 64-beam scan's evaluation.
inline __m128i FastSectors(__m128 x, __m128 y, __m128 sectors_per_radian, __m128 last, __m128 margin) {
    const __m128 sign = _mm_set1_ps(-0.0f), zero = _mm_setzero_ps();
    const auto select = [](__m128 mask, __m128 a, __m128 b) { return _mm_or_ps(_mm_and_ps(mask, a), _mm_andnot_ps(mask, b)); };
    const __m128 ax = _mm_andnot_ps(sign, x), ay = _mm_andnot_ps(sign, y);
    const __m128 steep = _mm_cmpgt_ps(ay, ax);
    const __m128 hi = select(steep, ay, ax), lo = select(steep, ax, ay);
    const __m128 t = _mm_div_ps(lo, hi), t2 = _mm_mul_ps(t, t);
    __m128 poly = _mm_set1_ps(kAtan[4]);
    for (int k = 3; k >= 0; --k) poly = _mm_add_ps(_mm_set1_ps(kAtan[k]), _mm_mul_ps(t2, poly));
    const __m128 a0 = _mm_mul_ps(t, poly);
    const __m128 a1 = select(steep, _mm_sub_ps(_mm_set1_ps(kPi / 2), a0), a0);
    const __m128 a2 = select(_mm_cmplt_ps(x, zero), _mm_sub_ps(_mm_set1_ps(kPi), a1), a1);
    const __m128 a = select(_mm_cmplt_ps(y, zero), _mm_sub_ps(_mm_set1_ps(2 * kPi), a2), a2);
    const __m128 unclamped = _mm_mul_ps(a, sectors_per_radian);
    const __m128 position = select(_mm_cmpgt_ps(unclamped, zero), select(_mm_cmplt_ps(unclamped, last), unclamped, last), zero);
    const __m128 nearest = _mm_cvtepi32_ps(_mm_cvttps_epi32(_mm_add_ps(position, _mm_set1_ps(0.5f))));
    const __m128 finite = _mm_set1_ps(std::numeric_limits<float>::max());
    const __m128 fast = _mm_and_ps(_mm_and_ps(_mm_cmple_ps(ax, finite), _mm_cmple_ps(ay, finite)),
                                   _mm_and_ps(_mm_cmpgt_ps(hi, zero), _mm_cmpge_ps(_mm_andnot_ps(sign, _mm_sub_ps(position, nearest)), margin)));
    const __m128i mask = _mm_castps_si128(fast);
    return _mm_or_si128(_mm_and_si128(mask, _mm_cvttps_epi32(position)), _mm_andnot_si128(mask, _mm_set1_epi32(-1)));
}
#endif

}  // namespace

void SectorOfAzimuth::operator()(const std::vector<Eigen::Vector3f>& points, std::vector<int>& sectors) const {
    const float last = static_cast<float>(num_sectors_);
    sectors.resize(points.size());
    std::size_t k = 0;
#if defined(__SSE2__)
    const __m128 per_radian = _mm_set1_ps(sectors_per_radian_), last4 = _mm_set1_ps(last), margin = _mm_set1_ps(margin_sectors_);
    for (; k + 4 <= points.size(); k += 4) {
        const Eigen::Vector3f* p = points.data() + k;
        const __m128 x = _mm_setr_ps(p[0].x(), p[1].x(), p[2].x(), p[3].x());
        const __m128 y = _mm_setr_ps(p[0].y(), p[1].y(), p[2].y(), p[3].y());
        _mm_storeu_si128(reinterpret_cast<__m128i*>(sectors.data() + k), FastSectors(x, y, per_radian, last4, margin));
    }
#endif
    for (; k < points.size(); ++k) sectors[k] = FastSector(points[k].x(), points[k].y(), sectors_per_radian_, last, margin_sectors_);
    for (std::size_t i = 0; i < points.size(); ++i)
        if (sectors[i] < 0) sectors[i] = ExactSector(points[i].x(), points[i].y(), num_sectors_);
}

}  // namespace revisit
