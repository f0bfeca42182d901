#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "core/se3.hpp"
#include "sim/generators.hpp"
#include "sim/scan_simulator.hpp"

namespace revisit {
namespace {

constexpr double kDeg = M_PI / 180.0;

double Elevation(const Eigen::Vector3d& d) { return std::atan2(d.z(), d.head<2>().norm()); }
double Azimuth(const Eigen::Vector3d& d) { return std::atan2(d.y(), d.x()); }

/// A city scan from a street, with one sensor.
class SensorInCity : public ::testing::Test {
  protected:
    static void SetUpTestSuite() {
        CityConfig config;
        config.blocks_x = 3;
        config.blocks_y = 3;
        world_ = new World(GenerateCity(config, 2));
        caster_ = new RayCaster(*world_);
    }
    static void TearDownTestSuite() {
        delete caster_;
        delete world_;
    }
    static Scan ScanWith(const SensorConfig& sensor, double height = 1.73) {
        // On the first street, in its lane, looking along it.
        const auto& edge = world_->streets.edges.front();
        Eigen::Vector2d tangent;
        const Eigen::Vector2d p = PolylinePoint(OffsetPolyline(edge.polyline, world_->lane_offset), 0.5 * edge.length, &tangent);
        SweepInput sweep;
        sweep.T_world_sensor = PoseFromXYZRPY(p.x(), p.y(), world_->ground.Height(p.x(), p.y()) + height, 0, 0,
                                              std::atan2(tangent.y(), tangent.x()));
        sweep.T_world_sensor_start = sweep.T_world_sensor;
        sweep.timestamp = 10.0;
        return SimulateScan(*caster_, sensor, MakeRays(sensor, 0), sweep, 1);
    }
    static World* world_;
    static RayCaster* caster_;
};
World* SensorInCity::world_ = nullptr;
RayCaster* SensorInCity::caster_ = nullptr;

TEST_F(SensorInCity, Hdl64HasKittiLikeCountsAndVerticalFieldOfView) {
    const SensorConfig sensor = Hdl64Sensor();
    EXPECT_EQ(sensor.NumRays(), 64u * 2048u);
    const Scan scan = ScanWith(sensor);
    EXPECT_GT(scan.points.size(), 100000u);
    EXPECT_LT(scan.points.size(), 131072u);
    EXPECT_EQ(scan.intensities.size(), scan.points.size());
    double lowest = 1e9, highest = -1e9;
    for (const auto& p : scan.points) {
        const double r = p.norm();
        EXPECT_GE(r, sensor.min_range - 0.1);
        EXPECT_LE(r, sensor.max_range + 0.1);
        lowest = std::min(lowest, Elevation(p.cast<double>()));
        highest = std::max(highest, Elevation(p.cast<double>()));
    }
    EXPECT_NEAR(lowest / kDeg, -24.33, 0.5);
    EXPECT_NEAR(highest / kDeg, 2.0, 0.5);
    for (float i : scan.intensities) ASSERT_TRUE(i >= 0.0f && i <= 1.0f);
}

TEST_F(SensorInCity, SpinningSensorsHaveTheirRings) {
    for (const auto& sensor : {Vlp16Sensor(), Hdl64Sensor(), Os128Sensor()}) {
        const Scan scan = ScanWith(sensor);
        std::set<long> rings;  // elevations in 0.05 degree bins: one bin per beam (noise is radial)
        for (const auto& p : scan.points) rings.insert(std::lround(Elevation(p.cast<double>()) / (0.05 * kDeg)));
        EXPECT_GE(rings.size(), sensor.vertical_angles.size() * 9 / 10) << sensor.label;
        EXPECT_LE(rings.size(), sensor.vertical_angles.size() * 2) << sensor.label;
        EXPECT_GT(scan.points.size(), sensor.NumRays() / 3) << sensor.label;
    }
}

TEST_F(SensorInCity, RosetteStaysInItsFieldOfViewAndNeverRepeats) {
    const SensorConfig sensor = LivoxAviaSensor();
    const auto first = MakeRays(sensor, 0), second = MakeRays(sensor, 1);
    ASSERT_EQ(first.size(), 24000u);
    double max_h = 0.0, max_v = 0.0;
    for (const auto& ray : first) {
        max_h = std::max(max_h, std::abs(std::atan2(ray.direction.y(), ray.direction.x())));
        max_v = std::max(max_v, std::abs(std::atan2(ray.direction.z(), ray.direction.x())));
    }
    EXPECT_NEAR(2.0 * max_h / kDeg, 70.4, 2.0);
    EXPECT_NEAR(2.0 * max_v / kDeg, 77.2, 2.0);
    EXPECT_GT((first[100].direction - second[100].direction).norm(), 1e-3);  // non-repetitive
    const Scan scan = ScanWith(sensor);
    EXPECT_GT(scan.points.size(), 9000u);  // the upper part of the field of view sees sky
    for (const auto& p : scan.points) ASSERT_GT(p.x(), 0.0f);  // forward-looking only
}

TEST_F(SensorInCity, PlanarLasersArePlanarWithTheirAperture) {
    for (double aperture : {180.0, 360.0}) {
        const SensorConfig sensor = PlanarLaserSensor(aperture);
        EXPECT_EQ(sensor.NumRays(), aperture > 359.0 ? 720u : 361u);
        const Scan scan = ScanWith(sensor, 0.5);
        EXPECT_GT(scan.points.size(), sensor.NumRays() / 3);
        double widest_point = 0.0, widest_ray = 0.0;
        for (const auto& p : scan.points) {
            ASSERT_EQ(p.z(), 0.0f);
            ASSERT_LE(p.norm(), sensor.max_range + 0.1);
            widest_point = std::max(widest_point, std::abs(Azimuth(p.cast<double>())));
        }
        for (const auto& ray : MakeRays(sensor, 0)) widest_ray = std::max(widest_ray, std::abs(Azimuth(ray.direction)));
        EXPECT_LE(widest_point, widest_ray + 1e-6);
        EXPECT_NEAR(widest_ray, 0.5 * aperture * kDeg, 0.5 * kDeg);
    }
}

TEST(DepthCamera, SeesAWallInItsFrustumWithinRange) {
    World world;
    world.boxes.push_back({Eigen::Vector2d(4.0, 0.0), Eigen::Vector2d(0.1, 20.0), 0.0, -1.0, 10.0, Material::kWall});
    const RayCaster caster(world);
    const SensorConfig sensor = DepthCameraSensor();
    EXPECT_EQ(sensor.NumRays(), 640u * 480u);
    SweepInput sweep;
    sweep.T_world_sensor = PoseFromXYZRPY(0, 0, 1.0, 0, 0, 0);
    sweep.T_world_sensor_start = sweep.T_world_sensor;
    const Scan scan = SimulateScan(caster, sensor, MakeRays(sensor, 0), sweep, 4);
    // The wall fills the image: all pixels but the dropouts return.
    EXPECT_GT(scan.points.size(), static_cast<std::size_t>(0.95 * 640 * 480));
    const double half_h = std::atan(319.5 / 525.0), half_v = std::atan(239.5 / 525.0);
    for (const auto& p : scan.points) {
        ASSERT_LE(std::abs(std::atan2(p.y(), p.x())), half_h + 1e-3);
        ASSERT_LE(std::abs(std::atan2(p.z(), p.x())), half_v + 1e-3);
        if (p.z() < -0.9) continue;  // the floor, 1 m below, fills the bottom rows up to ~2.2 m
        ASSERT_NEAR(p.x(), 3.9, 0.35);  // wall face at x = 3.9; noise sigma <= 5 cm out to the corners (~5.5 sigma)
        ASSERT_LE(std::abs(std::atan2(p.y(), p.x())), half_h + 1e-3);
        ASSERT_LE(std::abs(std::atan2(p.z(), p.x())), half_v + 1e-3);
    }
}

TEST(MotionDistortion, PointTimesSpanTheSweepAndDeskewingRestoresTheWall) {
    World world;
    world.boxes.push_back({Eigen::Vector2d(30.0, 0.0), Eigen::Vector2d(0.5, 30.0), 0.0, -1.0, 10.0, Material::kWall});
    const RayCaster caster(world);
    SensorConfig sensor = Vlp16Sensor();
    sensor.range_noise = 0.0;
    sensor.beam_range_sigma = 0.0;  // a calibration residual is a range error too
    sensor.dropout = 0.0;
    sensor.motion_distortion = true;
    SweepInput sweep;
    sweep.T_world_sensor_start = PoseFromXYZRPY(0, 0, 2.0, 0, 0, 0);
    sweep.T_world_sensor = PoseFromXYZRPY(2.0, 0, 2.0, 0, 0, 0.1);  // 20 m/s and turning
    sweep.timestamp = 1.0;
    const Scan scan = SimulateScan(caster, sensor, MakeRays(sensor, 0), sweep, 4);
    ASSERT_EQ(scan.point_times.size(), scan.points.size());
    ASSERT_GT(scan.points.size(), 1000u);
    const Vector6d motion = LogSE3(sweep.T_world_sensor_start.inverse() * sweep.T_world_sensor);
    double distorted = 0.0, deskewed = 0.0;
    for (std::size_t i = 0; i < scan.points.size(); ++i) {
        const double t = scan.point_times[i];
        ASSERT_GE(t, -0.1 - 1e-6);
        ASSERT_LE(t, 1e-6);
        // The wall's face is x = 29.5 in the world.
        const Eigen::Vector3d naive = sweep.T_world_sensor * scan.points[i].cast<double>();
        const Eigen::Isometry3d T_world_at_t = sweep.T_world_sensor_start * ExpSE3((1.0 + t / 0.1) * motion);
        const Eigen::Vector3d corrected = T_world_at_t * scan.points[i].cast<double>();
        if (corrected.z() < 0.3) continue;  // ground
        distorted = std::max(distorted, std::abs(naive.x() - 29.5));
        deskewed = std::max(deskewed, std::abs(corrected.x() - 29.5));
    }
    EXPECT_GT(distorted, 1.0);   // without deskewing the wall is smeared over metres
    EXPECT_LT(deskewed, 1e-3);   // with the constant-velocity poses every point is back on the wall
}

}  // namespace
}  // namespace revisit
