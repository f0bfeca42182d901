// The 2D aperture check on real logs: it corrects what is wrong and keeps what is right.
#include "settings/laser_aperture.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "config/config.hpp"
#include "settings/auto_settings.hpp"
#include "test_data.hpp"

namespace revisit {
namespace {

constexpr double kDeg = M_PI / 180.0;

/// The key frames of a carmen_kitti log as a laser's beams (`beams` over 180 deg, CARMEN's convention
/// beam i at -90 + i * 180 / (n - 1) deg), stated as `stated_deg`, with its reference poses as the prior.
std::vector<Scan> CarmenBeams(const std::string& name, int beams, double stated_deg, int count) {
    const auto dir = test::SharedData("carmen_kitti/" + name);
    std::ifstream poses(dir / "poses.txt");
    std::vector<Scan> scans;
    std::string line;
    for (int index = 0; index < count && std::getline(poses, line); ++index) {
        std::istringstream fields(line);
        Eigen::Matrix<double, 3, 4> m;
        for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 4; ++c) fields >> m(r, c);
        char file[32];
        std::snprintf(file, sizeof(file), "%06d.bin", index);
        std::FILE* f = std::fopen((dir / "velodyne" / file).c_str(), "rb");
        if (f == nullptr) break;
        std::vector<float> raw(4 * 4096);
        const std::size_t read = std::fread(raw.data(), sizeof(float), raw.size(), f);
        std::fclose(f);
        PlanarBeams planar;
        planar.ranges.assign(static_cast<std::size_t>(beams), 0.f);
        planar.aperture = planar.stated_aperture = stated_deg * kDeg;
        for (std::size_t i = 0; i + 3 < read; i += 4) {
            const double angle = std::atan2(raw[i + 1], raw[i]);
            const long beam = std::lround((angle + 0.5 * M_PI) / (M_PI / (beams - 1)));
            if (beam >= 0 && beam < beams) planar.ranges[static_cast<std::size_t>(beam)] = std::hypot(raw[i], raw[i + 1]);
        }
        Scan scan;
        scan.index = static_cast<std::size_t>(index);
        Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
        T.matrix().topRows<3>() = m;
        scan.T_odom_sensor = T;
        scan.planar_beams = std::move(planar);
        scans.push_back(std::move(scan));
    }
    return scans;
}

std::optional<ApertureEstimate> Check(const std::vector<Scan>& scans) {
    ApertureChecker checker;
    for (const auto& scan : scans) checker.Add(scan);
    return checker.Estimate();
}

TEST(LaserAperture, KeepsTheRightApertureOfA361BeamLogWhetherStatedAs180Or180_5) {
    REVISIT_REQUIRE_DATA(test::SharedData("carmen_kitti/seattle/poses.txt"));
    for (const double stated : {180.0, 180.5}) {
        const auto estimate = Check(CarmenBeams("seattle", 361, stated, 241));
        ASSERT_TRUE(estimate) << "no pairs";
        EXPECT_FALSE(estimate->contradicts) << estimate->Describe();
    }
}

TEST(LaserAperture, Corrects90To180OnA181BeamLogStatingHalfItsAperture) {
    REVISIT_REQUIRE_DATA(test::SharedData("carmen_kitti/orebro/poses.txt"));
    const auto estimate = Check(CarmenBeams("orebro", 181, 90.0, 237));
    ASSERT_TRUE(estimate) << "no pairs";
    EXPECT_TRUE(estimate->contradicts) << estimate->Describe();
    EXPECT_DOUBLE_EQ(estimate->measured_deg, 180.0) << estimate->Describe();
}

TEST(LaserAperture, CorrectsIntelsStated90DegreesFromTheGeometry) {
    const auto intel = test::SharedData("radish/intel.rawlog");
    REVISIT_REQUIRE_DATA(intel);
    PipelineConfig config;
    const auto settings = ConfigureFromData(config, intel);
    ASSERT_TRUE(settings.aperture);
    EXPECT_TRUE(settings.aperture->contradicts) << settings.aperture->Describe();
    EXPECT_DOUBLE_EQ(config.input.laser_aperture_deg, 180.0) << settings.aperture->Describe();
}

}  // namespace
}  // namespace revisit
