#pragma once
/// ScanContext's azimuthal bin of a point (scan_context.hpp) without an arctangent call for almost
/// every point: std::atan2 was over half of a cached evaluation's CPU.
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <vector>

namespace revisit {

/// SCManager's 1-based bin of value / max in count bins: clamp(ceil(value / max * count), 1, count),
/// in single precision. Inline: MakeScanContext calls it per point.
inline int ScanContextBin(float value, float max, int count) {
    const int bin = static_cast<int>(std::ceil(value / max * static_cast<float>(count)));
    return std::max(1, std::min(count, bin));
}

/// The 0-based sector of point (x, y), as SCManager: the azimuth std::atan2(y, x) in single-precision
/// degrees, moved to [0, 360), then ScanContextBin(azimuth, 360, num_sectors) - 1.
int ExactSector(float x, float y, int num_sectors);

/// The sectors ExactSector gives, from a polynomial arctangent (error <= 1.2e-5 rad, 1.3e-5 with its
/// float arithmetic: under 0.001 deg) wherever the azimuth lies more than kMarginDeg from a sector
/// boundary (multiples of 360 / num_sectors, 0 and 360 included). The exact path errs by less than
/// 0.0002 deg (a few ulp of atan2f and of the float products), so both sides of such a margin fall in
/// the same bin; nearer a boundary, and for a point at the origin or not finite, ExactSector decides
/// (0.3% of the points at 60 sectors).
class SectorOfAzimuth {
  public:
    static constexpr double kMarginDeg = 0.01;
    explicit SectorOfAzimuth(int num_sectors);
    /// sectors[k]: the sector of points[k] (its x and y).
    void operator()(const std::vector<Eigen::Vector3f>& points, std::vector<int>& sectors) const;

  private:
    int num_sectors_;
    float sectors_per_radian_;
    float margin_sectors_;
};

}  // namespace revisit
