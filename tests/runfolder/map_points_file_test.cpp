/// The stored local maps: what is written reads back on the grid, in a canonical order, byte-identical
/// whatever order the points came in; a damaged or cut file is an error naming it, never a map.
#include <gtest/gtest.h>
#include <zlib.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <random>

#include "core/error.hpp"
#include "runfolder/map_points_file.hpp"
#include "test_data.hpp"

namespace revisit {
namespace {
namespace fs = std::filesystem;

/// About what a highway map holds: a ground strip and a wall, one point per 0.5 m voxel somewhere in
/// it, around the map's origin (negative blocks too). `count` points at most.
std::vector<Eigen::Vector3f> MapLikePoints(std::size_t count, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> offset(0.f, 0.5f), noise(-0.05f, 0.05f);
    std::vector<Eigen::Vector3f> points;
    for (int i = -100; i < 100 && points.size() < count; ++i) {
        for (int k = -30; k < 30 && points.size() < count; ++k) points.emplace_back(0.5f * i + offset(rng), 0.5f * k + offset(rng), -1.8f + noise(rng));
        for (int h = 0; h < 8 && points.size() < count; ++h) points.emplace_back(0.5f * i + offset(rng), 16.f + noise(rng), -1.5f + 0.5f * h + offset(rng));
    }
    return points;
}

TEST(MapPointsFile, RoundTripIsTheSnappedMapWithinHalfAStepPerAxis) {
    const double step = MapPointStep(0.5);
    EXPECT_DOUBLE_EQ(step, 0.01);
    const auto points = MapLikePoints(20000, 3);
    const auto snapped = SnapToMapPointGrid(points, step);
    const auto bytes = EncodeMapPoints(points, step);
    const auto read = DecodeMapPoints(bytes, "map.rvmap");
    ASSERT_EQ(read.size(), points.size());
    EXPECT_EQ(read, snapped);                                  // bit for bit: the chain's points are the file's
    EXPECT_EQ(SnapToMapPointGrid(snapped, step), snapped);     // snapping twice changes nothing
    EXPECT_EQ(EncodeMapPoints(snapped, step), bytes);
    EXPECT_LT(bytes.size(), points.size() * 4);                // a quarter of KITTI .bin's 16 bytes at most

    // Every input point has its snapped copy within half a step per axis.
    auto sorted_input = points;
    auto by_value = [](const Eigen::Vector3f& a, const Eigen::Vector3f& b) {
        return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
    };
    std::vector<Eigen::Vector3f> resnapped;
    for (const auto& p : points) resnapped.push_back(SnapToMapPointGrid({p}, step).front());
    for (std::size_t i = 0; i < points.size(); ++i) {
        EXPECT_LE((resnapped[i] - points[i]).cwiseAbs().maxCoeff(), 0.5 * step + 1e-5);
    }
    std::sort(resnapped.begin(), resnapped.end(), by_value);
    auto read_sorted = read;
    std::sort(read_sorted.begin(), read_sorted.end(), by_value);
    EXPECT_EQ(read_sorted, resnapped);  // the same points, only reordered

    // Deterministic: the order the points came in does not change a byte.
    auto shuffled = points;
    std::shuffle(shuffled.begin(), shuffled.end(), std::mt19937(9));
    EXPECT_EQ(EncodeMapPoints(shuffled, step), bytes);

    EXPECT_TRUE(DecodeMapPoints(EncodeMapPoints({}, step), "empty.rvmap").empty());
    EXPECT_THROW(SnapToMapPointGrid({Eigen::Vector3f(std::nanf(""), 0.f, 0.f)}, step), std::invalid_argument);
}

TEST(MapPointsFile, DamagedOrTruncatedFilesAreErrorsNamingTheFile) {
    test::TempDir dir;
    const fs::path file = dir / "map_0007.rvmap";
    SaveMapPoints(file, MapLikePoints(3000, 5), MapPointStep(0.5));
    const std::string good = test::ReadFile(file);
    ASSERT_EQ(LoadMapPoints(file).size(), 3000u);

    const auto expect_named_error = [&](const std::string& bytes, const std::string& what) {
        std::ofstream(file, std::ios::binary | std::ios::trunc) << bytes;
        try {
            LoadMapPoints(file);
            ADD_FAILURE() << what << ": read as a good map";
        } catch (const DatasetError& e) {
            EXPECT_NE(std::string(e.what()).find("map_0007.rvmap"), std::string::npos) << what << ": " << e.what();
        }
    };
    for (std::size_t size : {std::size_t(0), std::size_t(3), std::size_t(20), std::size_t(36), std::size_t(40), good.size() / 2,
                             good.size() - 5, good.size() - 1}) {
        expect_named_error(good.substr(0, size), "cut at " + std::to_string(size));
    }
    expect_named_error(good + std::string(1, '\0'), "padded");
    for (std::size_t at = 0; at < good.size(); at += std::max<std::size_t>(1, good.size() / 97)) {
        std::string flipped = good;
        flipped[at] = char(flipped[at] ^ 0x10);
        expect_named_error(flipped, "bit flipped at " + std::to_string(at));
    }
    std::string kitti(16 * 100, '\0');  // a KITTI .bin of 100 points renamed
    expect_named_error(kitti, "not this format");
}

}  // namespace
}  // namespace revisit

namespace revisit {
namespace {

/// `bytes` with the double at `offset` replaced and the CRC-32 trailer made to match: a file whose
/// checksum is right but whose header is not.
std::string Resealed(std::string bytes, std::size_t offset, double value) {
    std::memcpy(bytes.data() + offset, &value, sizeof(value));
    const auto crc = static_cast<std::uint32_t>(
        crc32(crc32(0L, Z_NULL, 0), reinterpret_cast<const Bytef*>(bytes.data()), static_cast<uInt>(bytes.size() - 4)));
    std::memcpy(bytes.data() + bytes.size() - 4, &crc, sizeof(crc));
    return bytes;
}

TEST(MapPointsFile, ASealedFileWithAGridStepBeyondAnyMapVoxelIsAnError) {
    // Found by fuzz_map_points: a step of 1e300 m read back as infinite points.
    const std::vector<Eigen::Vector3f> points = {{1.f, 2.f, 3.f}, {-4.f, 5.f, 0.5f}};
    const std::string good = EncodeMapPoints(points, MapPointStep(0.5));
    ASSERT_EQ(DecodeMapPoints(good, "map_0000.rvmap").size(), 2u);
    constexpr std::size_t kStepOffset = 16;  // magic, version, count
    for (const double step : {1e300, 2.5, -0.01, std::nan("")}) {
        try {
            DecodeMapPoints(Resealed(good, kStepOffset, step), "map_0000.rvmap");
            ADD_FAILURE() << "step " << step << " read as good";
        } catch (const DatasetError& e) {
            EXPECT_NE(std::string(e.what()).find("map_0000.rvmap"), std::string::npos) << e.what();
            EXPECT_NE(std::string(e.what()).find("grid step"), std::string::npos) << e.what();
        }
    }
    // The largest step a run writes (a 100 m map voxel) still reads.
    EXPECT_EQ(DecodeMapPoints(Resealed(good, kStepOffset, 2.0), "map_0000.rvmap").size(), 2u);
}

}  // namespace
}  // namespace revisit
