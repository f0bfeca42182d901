// The correlative 2D scan match on real laser scans of a building (carmen_kitti: key frames of a
// 180-deg laser without any odometry) and the odometry that starts from it.
#include "odometry/correlative_matcher.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "odometry/lidar_odometry.hpp"
#include "test_data.hpp"

namespace revisit {
namespace {

std::filesystem::path CarmenDir(const std::string& name) { return test::SharedData("carmen_kitti/" + name); }

Scan LoadCarmenScan(const std::string& name, int index) {
    char file[32];
    std::snprintf(file, sizeof(file), "%06d.bin", index);
    const auto path = CarmenDir(name) / "velodyne" / file;
    std::vector<float> raw(std::filesystem::file_size(path) / sizeof(float));
    std::FILE* f = std::fopen(path.c_str(), "rb");
    const std::size_t read = f ? std::fread(raw.data(), sizeof(float), raw.size(), f) : 0;
    if (f) std::fclose(f);
    Scan scan;
    scan.index = static_cast<std::size_t>(index);
    scan.timestamp = index;
    for (std::size_t i = 0; i + 3 < read; i += 4) scan.points.emplace_back(raw[i], raw[i + 1], raw[i + 2]);
    return scan;
}

/// The reference poses (3x4 rows) as planar isometries.
std::vector<Eigen::Isometry3d> LoadPoses(const std::string& name) {
    std::vector<Eigen::Isometry3d> poses;
    std::ifstream in(CarmenDir(name) / "poses.txt");
    std::string line;
    while (std::getline(in, line)) {
        std::istringstream fields(line);
        Eigen::Matrix<double, 3, 4> m;
        for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 4; ++c) fields >> m(r, c);
        Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
        T.matrix().topRows<3>() = m;
        poses.push_back(T);
    }
    return poses;
}

double Yaw(const Eigen::Isometry3d& T) { return std::atan2(T.linear()(1, 0), T.linear()(0, 0)); }

Eigen::Isometry3d Planar(double x, double y, double yaw) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    T.translation() = Eigen::Vector3d(x, y, 0.0);
    return T;
}

std::vector<Eigen::Vector3d> Points(const Scan& scan, const Eigen::Isometry3d& T = Eigen::Isometry3d::Identity()) {
    std::vector<Eigen::Vector3d> points;
    for (const auto& p : scan.points) points.push_back(T * p.cast<double>());
    return points;
}

TEST(CorrelativeMatcher, RecoversAKnownOffsetBetweenTwoRealScans) {
    REVISIT_REQUIRE_DATA(CarmenDir("seattle") / "poses.txt");
    const auto poses = LoadPoses("seattle");
    CorrelativeMatchConfig config;
    int checked = 0;
    // Consecutive key frames (0.5-1 m and up to ~30 deg apart in this log).
    for (int i = 10; i + 2 < static_cast<int>(poses.size()); i += 23) {
        const Scan earlier = LoadCarmenScan("seattle", i), later = LoadCarmenScan("seattle", i + 1);
        const Eigen::Isometry3d T_truth = poses[i].inverse() * poses[i + 1];  // later in earlier's frame
        // Start 0.8 m and 25 deg away from the truth.
        const Eigen::Isometry3d T_start = T_truth * Planar(0.8 * std::cos(i), 0.8 * std::sin(i), (i % 2 ? 25.0 : -25.0) * M_PI / 180.0);
        const CorrelativeMatch match = MatchCorrelative2D(Points(earlier), Points(later), T_start, config);
        ASSERT_TRUE(match.valid);
        const Eigen::Isometry3d error = T_truth.inverse() * match.T_world_sensor;
        EXPECT_LT(error.translation().norm(), 0.15) << "pair " << i;
        EXPECT_LT(std::abs(Yaw(error)) * 180.0 / M_PI, 2.0) << "pair " << i;
        EXPECT_GT(match.score, 0.3) << "pair " << i;
        ++checked;
    }
    EXPECT_GE(checked, 8);
}

/// A corridor along x, 2 m wide, with a door (a 0.8 m gap in each wall) every 2 m: points every 5 cm.
std::vector<Eigen::Vector3d> DooredCorridor(double x_from, double x_to) {
    std::vector<Eigen::Vector3d> points;
    for (double x = x_from; x <= x_to; x += 0.05) {
        if (std::fmod(x - x_from, 2.0) < 0.8) continue;  // the doors
        points.emplace_back(x, -1.0, 0.0);
        points.emplace_back(x, 1.0, 0.0);
    }
    return points;
}

// Along a corridor whose doors repeat every 2 m, the pose 1.2 m ahead and the one 0.8 m behind explain
// a scan exactly as well: the pull towards the prediction (no motion) picks the one behind. The platform
// drives along its heading, and with the heading's pull the step forward wins.
TEST(CorrelativeMatcher, TheHeadingPicksTheForwardAliasOfACorridor) {
    const std::vector<Eigen::Vector3d> map = DooredCorridor(-20.0, 20.0);
    const Eigen::Isometry3d T_truth = Planar(1.2, 0.0, 0.0);  // the last pose at the origin, heading +x
    std::vector<Eigen::Vector3d> scan;
    for (const auto& p : DooredCorridor(-20.0, 20.0))
        if (std::abs(p.x() - 1.2) < 6.0) scan.push_back(T_truth.inverse() * p);
    CorrelativeMatchConfig config;
    config.resolution = 0.05;
    config.linear_window = 1.5;
    const CorrelativeMatch nearest = MatchCorrelative2D(map, scan, Eigen::Isometry3d::Identity(), config);
    ASSERT_TRUE(nearest.valid);
    EXPECT_NEAR(nearest.T_world_sensor.translation().x(), -0.8, 0.06) << "the alias behind, nearer the prediction";
    config.heading_prior = true;
    config.heading_origin = Eigen::Vector2d::Zero();
    config.heading_yaw = 0.0;
    const CorrelativeMatch ahead = MatchCorrelative2D(map, scan, Eigen::Isometry3d::Identity(), config);
    ASSERT_TRUE(ahead.valid);
    EXPECT_NEAR(ahead.T_world_sensor.translation().x(), 1.2, 0.06);
    EXPECT_NEAR(ahead.T_world_sensor.translation().y(), 0.0, 0.06);
    EXPECT_NEAR(ahead.score, nearest.score, 0.01) << "both aliases explain the scan equally";
}

/// The odometry with the settings the data gives these logs (a 2D laser: x, y, yaw; 5 cm voxels).
OdometryConfig PlanarConfig() {
    OdometryConfig config;
    config.planar = true;
    config.max_range = 70.0;
    config.min_range = 0.3;
    config.voxel_size = 0.05;
    config.initial_threshold = 0.1;
    config.min_motion_th = 0.005;
    return config;
}

// Every step of a 190 m walk through a building, 0.5-1 m and up to 80 deg apart, within 0.25 m and 3 deg.
TEST(CorrelativeOdometry, KeyFramesWithoutOdometryNeverDiverge) {
    const std::string log = "seattle";
    REVISIT_REQUIRE_DATA(CarmenDir(log) / "poses.txt");
    const auto poses = LoadPoses(log);
    LidarOdometry odometry(PlanarConfig());
    double worst_step = 0.0;
    int bad_steps = 0;
    for (int i = 0; i < static_cast<int>(poses.size()); ++i) {
        odometry.RegisterScan(LoadCarmenScan(log, i));
        EXPECT_FALSE(odometry.LastStats().degenerate) << odometry.LastStats().warning;
        if (i == 0) continue;
        const Eigen::Isometry3d truth = poses[i - 1].inverse() * poses[i];
        const Eigen::Isometry3d estimate = odometry.poses()[i - 1].inverse() * odometry.poses()[i];
        const Eigen::Isometry3d error = truth.inverse() * estimate;
        worst_step = std::max(worst_step, error.translation().norm());
        if (error.translation().norm() > 0.25 || std::abs(Yaw(error)) > 3.0 * M_PI / 180.0) {
            ++bad_steps;
            ADD_FAILURE() << "step " << i << ": error " << error.translation().norm() << " m, " << Yaw(error) * 180.0 / M_PI
                          << " deg (the truth moved " << truth.translation().norm() << " m, " << Yaw(truth) * 180.0 / M_PI << " deg)";
        }
    }
    EXPECT_EQ(odometry.NumDegenerateFrames(), 0u);
    EXPECT_EQ(bad_steps, 0) << "of " << poses.size() - 1 << " steps, worst " << worst_step << " m";
    EXPECT_TRUE(odometry.LastStats().correlative_used);
}

/// Registers scans first..last of `log` and counts the steps (but `skipped`) off the truth by more
/// than `metres` or `degrees`, each reported as a failure.
template <typename PoseList>
int RegisterAndCountBadSteps(LidarOdometry& odometry, const std::string& log, const PoseList& poses, int first, int last,
                             int skipped, double metres, double degrees) {
    int bad_steps = 0;
    for (int i = first; i <= last; ++i) {
        odometry.RegisterScan(LoadCarmenScan(log, i));
        EXPECT_FALSE(odometry.LastStats().degenerate) << odometry.LastStats().warning;
        if (i == first || i == skipped) continue;
        const Eigen::Isometry3d truth = poses[i - 1].inverse() * poses[i];
        const auto& estimated = odometry.poses();
        const Eigen::Isometry3d estimate = estimated[i - first - 1].inverse() * estimated[i - first];
        const Eigen::Isometry3d error = truth.inverse() * estimate;
        if (error.translation().norm() > metres || std::abs(Yaw(error)) > degrees * M_PI / 180.0) {
            ++bad_steps;
            ADD_FAILURE() << "step " << i << ": error " << error.translation().norm() << " m, " << Yaw(error) * 180.0 / M_PI
                          << " deg (the truth moved " << truth.translation().norm() << " m, " << Yaw(truth) * 180.0 / M_PI << " deg)";
        }
    }
    return bad_steps;
}

/// The settings the data gives orebro (0.2 m voxels).
OdometryConfig OrebroSettings() {
    OdometryConfig config;
    config.planar = true;
    config.max_range = 30.0;
    config.min_range = 0.25;
    config.voxel_size = 0.2;
    config.initial_threshold = 0.4;
    config.min_motion_th = 0.02;
    return config;
}

// Orebro's corridors, key frames 1-3 m and up to 45 deg apart: the likelihood's peaks along a
// corridor differ by ~2%, less than a one-voxel grid's sampling loss (12%), and the search picked a
// pose 1-2 m off (steps 17, 19, 25 before). Settings the data gives the log (0.2 m voxels).
TEST(CorrelativeOdometry, CorridorStepsFollowTheTruth) {
    const std::string log = "orebro";
    REVISIT_REQUIRE_DATA(CarmenDir(log) / "poses.txt");
    const auto poses = LoadPoses(log);
    const OdometryConfig config = OrebroSettings();
    LidarOdometry odometry(config);
    const int first = 0, last = 60;
    const int beyond_window = 5;  // its 2.9 m step lies beyond the 1.5 m window around the prediction: not claimed
    ASSERT_GT(static_cast<int>(poses.size()), last);
    const int bad_steps = RegisterAndCountBadSteps(odometry, log, poses, first, last, beyond_window, 0.5, 6.0);
    EXPECT_EQ(bad_steps, 0);
}

/// The settings the data gives belgioioso (0.1 m voxels).
OdometryConfig BelgioiosoSettings() {
    OdometryConfig config;
    config.planar = true;
    config.max_range = 30.0;
    config.min_range = 0.8;
    config.voxel_size = 0.1;
    config.initial_threshold = 0.2;
    config.min_motion_th = 0.01;
    return config;
}

// Belgioioso's scan 192 sees a corridor an earlier pass mapped: that pass lies in the map where the
// odometry's drift put it, and the scan registered to it, 0.42 m and 1.6 deg off the scans just
// before (the map that starts there was then false at its first scan). With a map of the last range's
// worth of travel every step follows the truth. Settings the data gives the log (0.1 m voxels).
TEST(CorrelativeOdometry, AMapOfRecentTravelKeepsADriftedEarlierPassOut) {
    const std::string log = "belgioioso";
    REVISIT_REQUIRE_DATA(CarmenDir(log) / "poses.txt");
    const auto poses = LoadPoses(log);
    OdometryConfig config = BelgioiosoSettings();
    config.map_travel_horizon = config.max_range;
    LidarOdometry odometry(config);
    const int bad_steps =
        RegisterAndCountBadSteps(odometry, log, poses, 0, static_cast<int>(poses.size()) - 1, -1, 0.25, 3.0);
    EXPECT_EQ(bad_steps, 0);
}

// The same scan with the whole map kept (KISS-ICP's map, which orebro's corridors need to tell their
// aliases apart): each frame is also registered to the last range's worth of travel, and scan 192's
// pull onto the drifted pass leaves its recent walls behind (31 of 147 points within a voxel of them,
// 74 at the recent travel's own pose). Without the check the step is off; with it every step follows
// the truth.
TEST(CorrelativeOdometry, TheRecentTravelOverrulesAPullOntoADriftedEarlierPass) {
    const std::string log = "belgioioso";
    REVISIT_REQUIRE_DATA(CarmenDir(log) / "poses.txt");
    const auto poses = LoadPoses(log);
    OdometryConfig config = BelgioiosoSettings();
    ASSERT_TRUE(config.recent_travel_check);  // the default
    const int last = 200;
    ASSERT_GT(static_cast<int>(poses.size()), last);
    LidarOdometry checked(config);
    const int bad_steps = RegisterAndCountBadSteps(checked, log, poses, 0, last, -1, 0.25, 3.0);
    EXPECT_EQ(bad_steps, 0);
    config.recent_travel_check = false;
    LidarOdometry unchecked(config);
    for (int i = 0; i <= 191; ++i) unchecked.RegisterScan(LoadCarmenScan(log, i));
    unchecked.RegisterScan(LoadCarmenScan(log, 192));
    const auto& p = unchecked.poses();
    const Eigen::Isometry3d error = (poses[191].inverse() * poses[192]).inverse() * (p[191].inverse() * p[192]);
    EXPECT_GT(error.translation().norm(), 0.25) << "without the check scan 192 follows the drifted pass";
}

// Orebro's whole walk (237 key frames, 1-3 m and spins of up to 77 deg through a grid of corridors
// with doors about 2.4 m apart). Without the heading's pull, scan 133 took the alias a door spacing
// behind (2.5 m off) and scans 137-138, spins in place, a corridor sideways (1.7 and 0.7 m off). With
// it every step but scan 5 (a 3 m step beyond the window) is within 0.5 m and 6 deg of the reference.
TEST(CorrelativeOdometry, TheHeadingKeepsCorridorAliasesBehindAndBesideOut) {
    const std::string log = "orebro";
    REVISIT_REQUIRE_DATA(CarmenDir(log) / "poses.txt");
    const auto poses = LoadPoses(log);
    OdometryConfig config = OrebroSettings();
    ASSERT_TRUE(config.correlative_heading_prior);  // the default
    const int beyond_window = 5;
    LidarOdometry odometry(config);
    EXPECT_EQ(RegisterAndCountBadSteps(odometry, log, poses, 0, static_cast<int>(poses.size()) - 1, beyond_window, 0.5, 6.0), 0);
    config.correlative_heading_prior = false;
    LidarOdometry without(config);
    for (int i = 0; i <= 133; ++i) without.RegisterScan(LoadCarmenScan(log, i));
    const auto& p = without.poses();
    const Eigen::Isometry3d error = (poses[132].inverse() * poses[133]).inverse() * (p[132].inverse() * p[133]);
    EXPECT_GT(error.translation().norm(), 1.0) << "without the heading scan 133 takes the alias behind";
}

TEST(CorrelativeOdometry, ARoomTurnedByNinetyDegreesContradictsTheBeamsOfTheSpinBeforeIt) {
    REVISIT_REQUIRE_DATA(CarmenDir("orebro") / "poses.txt");
    const auto poses = LoadPoses("orebro");
    // Orebro's scans 0-47 at their reference poses (the last four: spins in place), as the odometry's
    // map and its beams.
    constexpr double kVoxel = 0.2, kMargin = 2 * kVoxel;
    FreeSpace2D free(kVoxel);
    VoxelHashMap map(kVoxel, 20);
    for (int i = 0; i < 48; ++i) {
        const auto returns = Points(LoadCarmenScan("orebro", i), poses[static_cast<std::size_t>(i)]);
        free.AddBeams(poses[static_cast<std::size_t>(i)].translation(), returns, kMargin);
        map.AddPoints(returns);
    }
    // Scan 48 at its reference pose, and at the pose turned ~90 deg further that a wider correlative
    // search took with 3 cm of range noise (its step from scan 47: -0.85 m, 0.60 m, 123.6 deg).
    const auto scan = Points(LoadCarmenScan("orebro", 48));
    const BeamConflicts at_truth = CountBeamConflicts(free, map, scan, poses[48], kMargin);
    const BeamConflicts turned = CountBeamConflicts(free, map, scan, poses[47] * Planar(-0.85, 0.60, 123.6 * M_PI / 180.0), kMargin);
    // Measured: 0 returns in crossed space and 58 of 179 beams through a mapped point (people, chair
    // legs, a wall grazed) at the truth; 66 and 106 turned.
    EXPECT_LT(at_truth.returns_in_free, 10u);
    EXPECT_GT(turned.returns_in_free, 40u);
    EXPECT_GT(turned.beams_through_walls, at_truth.beams_through_walls + 30);
    EXPECT_TRUE(ClearlyMore(static_cast<double>(turned.Total()), static_cast<double>(at_truth.Total())));
}

}  // namespace
}  // namespace revisit
