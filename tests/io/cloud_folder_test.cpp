#include <gtest/gtest.h>

#include <cstring>
#include <fstream>

#include "core/error.hpp"
#include "io/cloud_files.hpp"
#include "io/reader.hpp"
#include "io/trajectory_io.hpp"
#include "test_data.hpp"

namespace revisit {
namespace {

void WriteBytes(const std::filesystem::path& file, const std::string& header, const std::vector<char>& body = {}) {
    std::ofstream out(file, std::ios::binary);
    out << header;
    out.write(body.data(), static_cast<std::streamsize>(body.size()));
}

template <typename T>
void Put(std::vector<char>& bytes, T value) {
    const auto* p = reinterpret_cast<const char*>(&value);
    bytes.insert(bytes.end(), p, p + sizeof(T));
}

TEST(Pcd, AsciiWithIntensityAndTime) {
    test::TempDir dir;
    WriteBytes(dir / "a.pcd",
               "# .PCD v0.7\nVERSION 0.7\nFIELDS x y z intensity t\nSIZE 4 4 4 4 4\nTYPE F F F F F\nCOUNT 1 1 1 1 1\n"
               "WIDTH 3\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS 3\nDATA ascii\n"
               "1 2 3 0.5 0.01\n4 5 6 0.25 0.02\nnan 0 0 0 0\n");
    const auto cloud = LoadPcd(dir / "a.pcd");
    ASSERT_EQ(cloud.points.size(), 2u);
    EXPECT_EQ(cloud.points[1], Eigen::Vector3f(4, 5, 6));
    EXPECT_FLOAT_EQ(cloud.intensities[0], 0.5f);
    EXPECT_FLOAT_EQ(cloud.point_times[1], 0.02f);
    EXPECT_EQ(cloud.non_finite, 1u);
}

TEST(Pcd, BinaryWithMixedTypesAndPadding) {
    test::TempDir dir;
    std::vector<char> body;
    for (int i = 0; i < 4; ++i) {
        Put<float>(body, 1.5f * i);
        Put<float>(body, -2.f * i);
        Put<double>(body, 0.25 * i);
        Put<std::uint16_t>(body, static_cast<std::uint16_t>(100 + i));  // ring, ignored
        Put<std::uint8_t>(body, static_cast<std::uint8_t>(10 * i));     // intensity as uint8
    }
    WriteBytes(dir / "b.pcd",
               "VERSION 0.7\nFIELDS x y z ring intensity\nSIZE 4 4 8 2 1\nTYPE F F F U U\nCOUNT 1 1 1 1 1\n"
               "WIDTH 4\nHEIGHT 1\nPOINTS 4\nDATA binary\n",
               body);
    const auto cloud = LoadPcd(dir / "b.pcd");
    ASSERT_EQ(cloud.points.size(), 4u);
    EXPECT_EQ(cloud.points[3], Eigen::Vector3f(4.5f, -6.f, 0.75f));
    EXPECT_FLOAT_EQ(cloud.intensities[2], 20.f);
    EXPECT_TRUE(cloud.point_times.empty());
}

TEST(Pcd, TruncatedAndUnsupportedFilesAreErrors) {
    test::TempDir dir;
    std::vector<char> body(12 * 2);
    WriteBytes(dir / "short.pcd", "FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nPOINTS 5\nDATA binary\n", body);
    EXPECT_THROW(LoadPcd(dir / "short.pcd"), DatasetError);
    WriteBytes(dir / "comp.pcd", "FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nPOINTS 1\nDATA binary_compressed\n");
    EXPECT_THROW(LoadPcd(dir / "comp.pcd"), DatasetError);
    WriteBytes(dir / "noxyz.pcd", "FIELDS a b\nSIZE 4 4\nTYPE F F\nPOINTS 1\nDATA ascii\n1 2\n");
    EXPECT_THROW(LoadPcd(dir / "noxyz.pcd"), DatasetError);
    WriteBytes(dir / "size.pcd", "FIELDS x y z\nSIZE 4 4 3\nTYPE F F F\nPOINTS 1\nDATA ascii\n1 2 3\n");
    EXPECT_THROW(LoadPcd(dir / "size.pcd"), DatasetError);
}

TEST(Ply, BinaryRoundTripIsBitExact) {
    test::TempDir dir;
    std::vector<Eigen::Vector3f> points{{0.1f, 0.2f, 0.3f}, {-1e6f, 3.4028e38f, 1e-30f}};
    SavePly(dir / "p.ply", points, {0.5f, 0.75f});
    const auto cloud = LoadPly(dir / "p.ply");
    ASSERT_EQ(cloud.points.size(), 2u);
    EXPECT_EQ(std::memcmp(cloud.points[1].data(), points[1].data(), 12), 0);
    EXPECT_FLOAT_EQ(cloud.intensities[1], 0.75f);
}

TEST(Ply, AsciiWithFacesAfterVertices) {
    test::TempDir dir;
    WriteBytes(dir / "a.ply",
               "ply\nformat ascii 1.0\ncomment made by hand\nelement vertex 3\nproperty float x\nproperty float y\n"
               "property float z\nproperty uchar red\nelement face 1\nproperty list uchar int vertex_indices\n"
               "end_header\n0 0 0 255\n1 0 0 255\n0 1 2 255\n3 0 1 2\n");
    const auto cloud = LoadPly(dir / "a.ply");
    ASSERT_EQ(cloud.points.size(), 3u);
    EXPECT_EQ(cloud.points[2], Eigen::Vector3f(0, 1, 2));
    EXPECT_TRUE(cloud.intensities.empty());
}

TEST(Ply, BigEndianAndBadMagicAreErrors) {
    test::TempDir dir;
    WriteBytes(dir / "be.ply", "ply\nformat binary_big_endian 1.0\nelement vertex 0\nproperty float x\nend_header\n");
    EXPECT_THROW(LoadPly(dir / "be.ply"), DatasetError);
    WriteBytes(dir / "x.ply", "PCD\n");
    EXPECT_THROW(LoadPly(dir / "x.ply"), DatasetError);
}

TEST(CloudFolder, ReadsSortedPlyScansWithTumPoses) {
    test::TempDir dir;
    for (int i = 2; i >= 0; --i) {
        SavePly(dir / ("scan_" + std::to_string(i) + ".ply"), {Eigen::Vector3f(static_cast<float>(i), 0, 0)});
    }
    Trajectory gt;
    for (int i = 0; i < 3; ++i) {
        gt.timestamps.push_back(10.0 + i);
        Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
        T.translation().y() = 2.0 * i;
        gt.poses.push_back(T);
    }
    WriteTumPoses(dir / "poses.txt", gt);
    auto reader = OpenDataset(dir.path());
    EXPECT_EQ(reader->Info().format, "ply");
    for (int i = 0; i < 3; ++i) {
        const auto scan = reader->Next();
        ASSERT_TRUE(scan);
        EXPECT_EQ(scan->points[0].x(), static_cast<float>(i));
        EXPECT_DOUBLE_EQ(scan->timestamp, 10.0 + i);
        EXPECT_NEAR(scan->T_world_sensor->translation().y(), 2.0 * i, 1e-9);
    }
    EXPECT_FALSE(reader->Next());
}

TEST(CloudFolder, MixedFormatsAreRefused) {
    test::TempDir dir;
    SavePly(dir / "a.ply", {Eigen::Vector3f(1, 2, 3)});
    WriteBytes(dir / "b.pcd", "FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nPOINTS 0\nDATA ascii\n");
    EXPECT_THROW(OpenDataset(dir.path()), DatasetError);
}

}  // namespace
}  // namespace revisit
