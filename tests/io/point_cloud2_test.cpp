/// PointCloud2 layouts the shared recordings do not have, LaserScan beams, and pose pairing by stamp.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "io/bag_poses.hpp"
#include "io/point_cloud2.hpp"

namespace revisit {
namespace {

/// A cloud built field by field: each point's fields written in order at their offsets.
struct CloudBuilder {
    PointCloud2Msg msg;
    std::vector<std::uint8_t> bytes;
    void Field(const std::string& name, std::uint32_t offset, std::uint8_t datatype) { msg.fields.push_back({name, offset, datatype, 1}); }
    template <typename T>
    void Put(std::size_t point, std::uint32_t offset, T value, bool big_endian = false) {
        std::uint8_t raw[sizeof(T)];
        std::memcpy(raw, &value, sizeof(T));
        if (big_endian) std::reverse(raw, raw + sizeof(T));
        std::memcpy(bytes.data() + point * msg.point_step + offset, raw, sizeof(T));
    }
    const PointCloud2Msg& Done() {
        msg.data = bytes.data();
        msg.data_size = bytes.size();
        return msg;
    }
};

TEST(PointCloud2, Float64BigEndianPaddedWithIntensityAndNaN) {
    CloudBuilder b;
    b.msg.height = 1, b.msg.width = 3, b.msg.point_step = 40, b.msg.row_step = 120, b.msg.is_bigendian = true;
    b.Field("x", 0, 8), b.Field("y", 8, 8), b.Field("z", 16, 8), b.Field("intensity", 24, 4);  // uint16
    b.bytes.resize(120);
    const double xs[3] = {1.5, NAN, -3.25};
    for (std::size_t i = 0; i < 3; ++i) {
        b.Put(i, 0, xs[i], true), b.Put(i, 8, 2.0 * double(i), true), b.Put(i, 16, 0.5, true);
        b.Put(i, 24, std::uint16_t(100 + i), true);
    }
    const CloudData cloud = PointsFromCloud2(b.Done());
    ASSERT_EQ(cloud.points.size(), 2u);
    EXPECT_EQ(cloud.non_finite, 1u);
    EXPECT_EQ(cloud.points[0], Eigen::Vector3f(1.5f, 0.f, 0.5f));
    EXPECT_EQ(cloud.points[1], Eigen::Vector3f(-3.25f, 4.f, 0.5f));
    EXPECT_EQ(cloud.intensities, (std::vector<float>{100.f, 102.f}));
}

TEST(PointCloud2, OrganizedRowsWithRowPadding) {
    CloudBuilder b;
    b.msg.height = 2, b.msg.width = 2, b.msg.point_step = 12, b.msg.row_step = 30;  // 6 bytes of row padding
    b.Field("x", 0, 7), b.Field("y", 4, 7), b.Field("z", 8, 7);
    b.bytes.assign(54, 0);
    for (int row = 0; row < 2; ++row)
        for (int col = 0; col < 2; ++col) std::memcpy(b.bytes.data() + row * 30 + col * 12, &(const float&)float(10 * row + col), 4);
    const CloudData cloud = PointsFromCloud2(b.Done());
    ASSERT_EQ(cloud.points.size(), 4u);
    EXPECT_EQ(cloud.points[3].x(), 11.f);
    EXPECT_EQ(cloud.points[2].x(), 10.f);
}

/// Per-point times: integer ns (Ouster t, Livox offset_time), integer us, float s, absolute float64 s.
template <typename T>
std::vector<float> Times(const char* name, std::uint8_t datatype, std::vector<T> values, std::int64_t stamp_ns = 0) {
    CloudBuilder b;
    b.msg.stamp_ns = stamp_ns;
    b.msg.height = 1, b.msg.width = std::uint32_t(values.size()), b.msg.point_step = 12 + 8;
    b.msg.row_step = b.msg.width * b.msg.point_step;
    b.Field("x", 0, 7), b.Field("y", 4, 7), b.Field("z", 8, 7), b.Field(name, 12, datatype);
    b.bytes.assign(b.msg.row_step, 0);
    for (std::size_t i = 0; i < values.size(); ++i) b.Put(i, 12, values[i]);
    return PointsFromCloud2(b.Done()).point_times;
}

TEST(PointCloud2, PointTimesInSecondsRelativeToTheStamp) {
    EXPECT_EQ(Times<std::uint32_t>("t", 6, {0, 50'000'000, 100'000'000}), (std::vector<float>{0.f, 0.05f, 0.1f}));
    EXPECT_EQ(Times<std::uint32_t>("offset_time", 6, {0, 2'000'000}), (std::vector<float>{0.f, 0.002f}));  // 2 ms in ns
    EXPECT_EQ(Times<std::uint32_t>("time", 6, {0, 50'000, 100'000}), (std::vector<float>{0.f, 0.05f, 0.1f}));  // us
    EXPECT_EQ(Times<float>("time", 7, {-0.1f, 0.f}), (std::vector<float>{-0.1f, 0.f}));
    const std::int64_t stamp = 1'700'000'000'000'000'000;
    const auto absolute = Times<double>("timestamp", 8, {1.7e9, 1.7e9 + 0.05}, stamp);
    ASSERT_EQ(absolute.size(), 2u);
    EXPECT_NEAR(absolute[0], 0.0, 1e-6);
    EXPECT_NEAR(absolute[1], 0.05, 1e-6);
}

TEST(PointCloud2, ACloudOfNoColumnsIsEmptyWhateverItsRows) {
    CloudBuilder b;
    b.msg.height = 4000000000u, b.msg.width = 0, b.msg.point_step = 12, b.msg.row_step = 0;
    b.Field("x", 0, 7), b.Field("y", 4, 7), b.Field("z", 8, 7);
    const CloudData cloud = PointsFromCloud2(b.Done());
    EXPECT_TRUE(cloud.points.empty());
    EXPECT_EQ(cloud.non_finite, 0u);
}

TEST(PointCloud2, LayoutsThatDoNotFitAreErrors) {
    CloudBuilder b;
    b.msg.height = 1, b.msg.width = 10, b.msg.point_step = 12, b.msg.row_step = 120;
    b.Field("x", 0, 7), b.Field("y", 4, 7), b.Field("z", 8, 7);
    b.bytes.assign(60, 0);  // half the points' bytes
    EXPECT_THROW(PointsFromCloud2(b.Done()), WireError);
    b.bytes.assign(120, 0);
    b.msg.fields[2].offset = 10;  // past point_step
    EXPECT_THROW(PointsFromCloud2(b.Done()), WireError);
    b.msg.fields[2] = {"z", 8, 9, 1};  // no such datatype
    EXPECT_THROW(PointsFromCloud2(b.Done()), WireError);
    b.msg.fields.pop_back();
    EXPECT_THROW(PointsFromCloud2(b.Done()), WireError);
}

TEST(LaserScan, BeamsInIncreasingAngleAndOutOfRangeAsNoReturn) {
    LaserScanMsg msg;
    msg.angle_min = float(-M_PI / 2), msg.angle_max = float(M_PI / 2), msg.angle_increment = float(M_PI / 2);
    msg.range_min = 0.1f, msg.range_max = 30.f;
    msg.ranges = {1.f, 50.f, NAN};
    std::size_t non_finite = 0;
    const Scan scan = ScanFromLaserScan(msg, 0.0, non_finite);
    ASSERT_EQ(scan.points.size(), 1u);
    EXPECT_NEAR(scan.points[0].y(), -1.f, 1e-6);
    EXPECT_EQ(non_finite, 1u);
    ASSERT_TRUE(scan.planar_beams);
    EXPECT_EQ(scan.planar_beams->ranges, (std::vector<float>{1.f, 0.f, 0.f}));
    EXPECT_NEAR(scan.planar_beams->aperture, M_PI, 1e-6);
}

PoseMsg At(std::int64_t t, double x) {
    PoseMsg pose;
    pose.stamp_ns = t;
    pose.T.translation().x() = x;
    return pose;
}

TEST(PoseSeries, PriorIsTheLatestOrInterpolatedReferenceWithinTolerance) {
    PoseSeries series;
    series.Add(At(300, 3.0));
    series.Add(At(100, 1.0));
    series.Sort();
    EXPECT_FALSE(series.Prior(99));
    EXPECT_EQ(series.Prior(100)->T.translation().x(), 1.0);
    EXPECT_DOUBLE_EQ(series.Prior(150)->T.translation().x(), 1.5);
    EXPECT_EQ(series.Prior(1000)->T.translation().x(), 3.0);
    EXPECT_DOUBLE_EQ(series.Reference(200, 100)->T.translation().x(), 2.0);
    EXPECT_EQ(series.Reference(120, 50)->T.translation().x(), 1.0);  // only the earlier one is close enough
    EXPECT_FALSE(series.Reference(200, 50));
    EXPECT_FALSE(series.Reference(400, 50));
}

TEST(StaticFrames, ChainsTransformsEitherWay) {
    StaticFrames frames;
    PoseMsg base_lidar;
    base_lidar.frame_id = "base_link", base_lidar.child_frame_id = "lidar";
    base_lidar.T.translation() = Eigen::Vector3d(0, 0, 1);
    PoseMsg base_imu = base_lidar;
    base_imu.child_frame_id = "imu";
    base_imu.T.translation() = Eigen::Vector3d(1, 0, 0);
    frames.Add(base_lidar), frames.Add(base_imu);
    EXPECT_TRUE(frames.Find("imu", "lidar")->translation().isApprox(Eigen::Vector3d(-1, 0, 1)));
    EXPECT_TRUE(frames.Find("lidar", "base_link")->translation().isApprox(Eigen::Vector3d(0, 0, -1)));
    EXPECT_FALSE(frames.Find("lidar", "map"));
}

}  // namespace
}  // namespace revisit
