#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "core/voxel.hpp"

namespace revisit {
namespace {

/// FloorToInt replaces std::floor and the cast in every voxel index: it must give the same integer
/// wherever the cast is defined, at whole numbers, just below and above them, and at both signs of zero.
template <typename Scalar>
void ExpectSameAsLibraryFloor(Scalar x) {
    EXPECT_EQ(FloorToInt(x), static_cast<int>(std::floor(x))) << x;
}

TEST(Voxel, FloorToIntIsTheLibraryFloorOverTheIntRange) {
    for (const double whole : {0.0, 1.0, -1.0, 2.0, -2.0, 1e6, -1e6, 2147483646.0, -2147483647.0}) {
        ExpectSameAsLibraryFloor(whole);
        ExpectSameAsLibraryFloor(std::nextafter(whole, -1e300));
        ExpectSameAsLibraryFloor(std::nextafter(whole, 1e300));
    }
    // Floats: whole from 2^24 on; their neighbours past 2^30 leave the int range.
    for (const float whole : {0.0f, 1.0f, -1.0f, 2.0f, -2.0f, 1e6f, -1e6f, 16777216.0f, -16777216.0f, 1073741824.0f, -1073741824.0f}) {
        ExpectSameAsLibraryFloor(whole);
        ExpectSameAsLibraryFloor(std::nextafter(whole, -1e30f));
        ExpectSameAsLibraryFloor(std::nextafter(whole, 1e30f));
    }
    ExpectSameAsLibraryFloor(-0.0);
    ExpectSameAsLibraryFloor(-0.0f);
    ExpectSameAsLibraryFloor(std::numeric_limits<double>::denorm_min());
    ExpectSameAsLibraryFloor(-std::numeric_limits<double>::denorm_min());
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> u(-1e5, 1e5);
    for (int i = 0; i < 100000; ++i) {
        const double x = u(rng);
        ExpectSameAsLibraryFloor(x);
        ExpectSameAsLibraryFloor(static_cast<float>(x));
    }
}

TEST(Voxel, FloorVoxelIsTheVoxelOfEachAxis) {
    EXPECT_EQ(VoxelOf(Eigen::Vector3d(-0.25, 0.25, 1.0), 0.5), Voxel(-1, 0, 2));
    EXPECT_EQ(FloorVoxel(Eigen::Vector3f(-3.5f, 3.5f, -0.0f)), Voxel(-4, 3, 0));
}

}  // namespace
}  // namespace revisit
