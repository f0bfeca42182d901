#include "evaluation/azimuth_sector.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

namespace revisit {
namespace {

/// SCManager's sector written out independently: float atan2 in degrees, [0, 360), ceil, clamp.
int ReferenceSector(float x, float y, int num_sectors) {
    float deg = std::atan2(y, x) * static_cast<float>(180.0 / M_PI);
    if (deg < 0.0f) deg += 360.0f;
    const int bin = static_cast<int>(std::ceil(deg / 360.0f * static_cast<float>(num_sectors)));
    return std::max(1, std::min(num_sectors, bin)) - 1;
}

/// Every point's sector from SectorOfAzimuth (one batch, as MakeScanContext calls it) against the
/// reference; the first disagreement fails.
void ExpectExactSectors(const std::vector<Eigen::Vector3f>& points, int num_sectors) {
    std::vector<int> sectors;
    const SectorOfAzimuth sector_of(num_sectors);
    sector_of(points, sectors);
    ASSERT_EQ(sectors.size(), points.size());
    for (std::size_t k = 0; k < points.size(); ++k) {
        const float x = points[k].x(), y = points[k].y();
        ASSERT_EQ(sectors[k], ReferenceSector(x, y, num_sectors)) << num_sectors << " sectors at " << x << ", " << y;
        ASSERT_EQ(ExactSector(x, y, num_sectors), ReferenceSector(x, y, num_sectors));
    }
}

const int kSectorCounts[] = {1, 2, 3, 7, 60, 64, 360, 1000, 100000};

TEST(SectorOfAzimuth, RandomPointsGetTheExactSector) {
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> coordinate(-120.0f, 120.0f);
    std::uniform_real_distribution<float> small(-1e-3f, 1e-3f);
    for (const int sectors : kSectorCounts) {
        std::vector<Eigen::Vector3f> points;
        for (int k = 0; k < 400000; ++k) {
            // Mostly a lidar's scale; some points next to the axes and the origin.
            const float x = k % 10 == 0 ? small(rng) : coordinate(rng);
            const float y = k % 7 == 0 ? small(rng) : coordinate(rng);
            points.emplace_back(x, y, 1.0f);
        }
        ExpectExactSectors(points, sectors);
    }
}

TEST(SectorOfAzimuth, PointsOnAndNextToEveryBoundaryGetTheExactSector) {
    for (const int sectors : {1, 3, 7, 60, 64, 360}) {
        std::vector<Eigen::Vector3f> points;
        for (int b = 0; b <= sectors; ++b) {
            const double boundary = 2.0 * M_PI * b / sectors;
            // On the boundary, then angles stepping away from it through and past the margin.
            for (double offset_deg : {0.0, 1e-9, 1e-7, 1e-5, 1e-4, 1e-3, 0.005, 0.0099, 0.01, 0.0101, 0.011, 0.02, 0.1}) {
                for (const double sign : {-1.0, 1.0}) {
                    const double angle = boundary + sign * offset_deg * M_PI / 180.0;
                    for (const float radius : {0.01f, 1.0f, 7.3f, 80.0f, 1000.0f}) {
                        const float x = static_cast<float>(radius * std::cos(angle));
                        const float y = static_cast<float>(radius * std::sin(angle));
                        // The point itself and its float neighbours in every direction.
                        for (int dx = -3; dx <= 3; ++dx) {
                            for (int dy = -3; dy <= 3; ++dy) {
                                float px = x, py = y;
                                for (int s = 0; s < std::abs(dx); ++s) px = std::nextafter(px, dx > 0 ? 1e9f : -1e9f);
                                for (int s = 0; s < std::abs(dy); ++s) py = std::nextafter(py, dy > 0 ? 1e9f : -1e9f);
                                points.emplace_back(px, py, 0.0f);
                            }
                        }
                    }
                }
            }
        }
        ExpectExactSectors(points, sectors);
    }
}

TEST(SectorOfAzimuth, AxesSignedZerosAndNonFinitePointsGetTheExactSector) {
    const float inf = std::numeric_limits<float>::infinity(), nan = std::numeric_limits<float>::quiet_NaN();
    const float values[] = {0.0f, -0.0f, 1.0f, -1.0f, 1e-38f, -1e-38f, 1e-45f, 3e38f, -3e38f, inf, -inf};
    for (const int sectors : {1, 7, 60, 360}) {
        std::vector<Eigen::Vector3f> points;
        for (const float x : values)
            for (const float y : values) points.emplace_back(x, y, 0.0f);
        ExpectExactSectors(points, sectors);
        // NaN: whatever the exact rule does, the same.
        std::vector<int> sector;
        const SectorOfAzimuth sector_of(sectors);
        sector_of({{nan, 1.0f, 0.0f}, {1.0f, nan, 0.0f}, {nan, nan, 0.0f}}, sector);
        EXPECT_EQ(sector, (std::vector<int>{ExactSector(nan, 1.0f, sectors), ExactSector(1.0f, nan, sectors),
                                            ExactSector(nan, nan, sectors)}));
    }
}

TEST(SectorOfAzimuth, ADenseSweepOfAnglesAtSixtySectors) {
    // Every 1e-4 degree over the whole circle on a 30 m circle: the sweep crosses each boundary's
    // margin with a hundred points on each side.
    std::vector<Eigen::Vector3f> points;
    for (long k = 0; k < 3600000; ++k) {
        const double angle = k * 1e-4 * M_PI / 180.0;
        points.emplace_back(static_cast<float>(30.0 * std::cos(angle)), static_cast<float>(30.0 * std::sin(angle)), 0.0f);
    }
    ExpectExactSectors(points, 60);
}

}  // namespace
}  // namespace revisit
