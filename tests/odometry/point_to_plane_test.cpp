// The point-to-plane residual (odometry.residual) against KISS-ICP's point-to-point on what a sparse
// 16-ring sensor sees of walls (src/sim/README.md, "Sparse and narrow sensors"): each upward ring's
// line on a wall moves towards the horizon as the sensor approaches, so the map holds the earlier,
// higher lines of the wall ahead and the lower ones of the wall behind.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/se3.hpp"
#include "odometry/registration.hpp"
#include "odometry/voxel_hash_map.hpp"

namespace revisit {
namespace {

constexpr double kDeg = M_PI / 180.0;

/// Horizontal lines at `heights` on the wall x = `x` (y in [-10, 10], a point every 0.25 m).
void AddWallLines(double x, const std::vector<double>& heights, std::vector<Eigen::Vector3d>& points) {
    for (const double z : heights)
        for (double y = -10.0; y <= 10.0; y += 0.25) points.emplace_back(x, y, z);
}

/// The ground (z = -1.8) and side walls (y = +-8) of a 40 m street, sampled every `step` [m] from
/// `offset` [m] past the corner.
void AddGroundAndSideWalls(double offset, double step, std::vector<Eigen::Vector3d>& points) {
    for (double x = -20.0 + offset; x <= 20.0; x += step) {
        for (double y = -8.0 + offset; y <= 8.0; y += step) points.emplace_back(x, y, -1.8);
        for (double z = -1.8 + offset; z <= 6.0; z += step) {
            points.emplace_back(x, 8.0, z);
            points.emplace_back(x, -8.0, z);
        }
    }
}

/// A street 16 m wide: a densely sampled ground (z = -1.8) and side walls (y = +-8); the walls ahead
/// (x = 15) and behind (x = -15) only as the sparse lines of rings 2 degrees apart.
struct Street {
    std::vector<Eigen::Vector3d> map_points;
    std::vector<Eigen::Vector3d> scan_points;  ///< the current scan, sensor at the origin (the truth)
};

Street MakeStreet() {
    Street street;
    auto& map = street.map_points;
    AddGroundAndSideWalls(0.0, 0.3, map);
    // Earlier scans saw the upward rings higher on the wall ahead and lower on the wall behind.
    AddWallLines(15.0, {3.1, 3.4, 3.7, 4.0}, map);
    AddWallLines(-15.0, {1.4, 1.7, 2.0, 2.3}, map);
    // The current scan: the same ground and side walls, its ring lines between the map's.
    auto& scan = street.scan_points;
    AddGroundAndSideWalls(0.15, 0.9, scan);
    AddWallLines(15.0, {2.6}, scan);
    AddWallLines(-15.0, {2.8}, scan);
    return street;
}

double PitchDeg(const Eigen::Isometry3d& T) {
    return std::asin(std::clamp(-T.linear()(2, 0), -1.0, 1.0)) / kDeg;
}

IcpResult Register(const Street& street, bool point_to_plane) {
    VoxelHashMap map(1.0, 20);
    map.EnableNormals(point_to_plane);
    map.AddPoints(street.map_points);
    IcpParams params;
    params.max_correspondence_distance = 1.5;
    params.kernel = 0.5;
    params.point_to_plane = point_to_plane;
    return RegisterPointsToMap(street.scan_points, map, Eigen::Isometry3d::Identity(), params);
}

TEST(PointToPlane, SparseRingLinesOnWallsPullPointToPointInPitchButNotPointToPlane) {
    const Street street = MakeStreet();
    const IcpResult point_to_point = Register(street, false);
    const IcpResult point_to_plane = Register(street, true);
    ASSERT_TRUE(point_to_point.valid);
    ASSERT_TRUE(point_to_plane.valid);
    const double p2p_pitch = PitchDeg(point_to_point.T_world_sensor);
    const double p2pl_pitch = PitchDeg(point_to_plane.T_world_sensor);
    std::printf("pitch from the true pose: point-to-point %.4f deg, point-to-plane %.4f deg\n", p2p_pitch, p2pl_pitch);
    // Up ahead, down behind: the lines tilt the point-to-point estimate nose-up.
    EXPECT_GT(std::abs(p2p_pitch), 0.05);
    EXPECT_LT(std::abs(p2pl_pitch), 0.005);
    EXPECT_LT(point_to_plane.T_world_sensor.translation().norm(), 0.01);
    // Ground, side walls and the wall lines all span planes: the planes were used alone.
    EXPECT_TRUE(point_to_plane.planes_only);
    EXPECT_EQ(point_to_plane.plane_correspondences, point_to_plane.correspondences);
}

TEST(PointToPlane, ASingleRingLineIsNotTakenForAPlane) {
    // One ring's line on a wall is thin across the wall and vertically alike: a plane fit would give it
    // a vertical normal and turn its point-to-plane residual into the very pull it must avoid.
    VoxelHashMap map(1.0, 20);
    map.EnableNormals(true);
    std::vector<Eigen::Vector3d> line;
    for (double y = 0.05; y < 0.95; y += 0.1) line.emplace_back(10.5 + 0.002 * std::sin(37.0 * y), y, 2.5);
    map.AddPoints(line);
    const Eigen::Vector3d* nearest = map.FindNearest(Eigen::Vector3d(10.5, 0.5, 2.6), 1.0);
    ASSERT_NE(nearest, nullptr);
    EXPECT_EQ(map.NormalOf(nearest), nullptr);
    // A second line 0.3 m lower in the same voxel makes it a wall: the normal is horizontal, along x.
    std::vector<Eigen::Vector3d> second;
    for (double y = 0.05; y < 0.95; y += 0.1) second.emplace_back(10.5, y, 2.2);
    map.AddPoints(second);
    nearest = map.FindNearest(Eigen::Vector3d(10.5, 0.5, 2.6), 1.0);
    ASSERT_NE(nearest, nullptr);
    const Eigen::Vector3d* normal = map.NormalOf(nearest);
    ASSERT_NE(normal, nullptr);
    EXPECT_NEAR(std::abs(normal->x()), 1.0, 1e-3);
}

TEST(PointToPlane, A2DLasersWallLineGetsItsNormalWithinThePlane) {
    // A 2D laser's map: every point at one height. The 3D fit has no plane to find (the points span a
    // line), so without the in-plane mode a wall line has no normal; with it, the line's normal in x-y.
    std::vector<Eigen::Vector3d> wall;
    for (double y = 0.02; y < 0.5; y += 0.04) wall.emplace_back(2.05 + 0.003 * std::sin(31.0 * y), y, 0.0);
    for (const bool in_plane : {false, true}) {
        VoxelHashMap map(0.5, 20);
        map.EnableNormals(true, in_plane);
        map.AddPoints(wall);
        const Eigen::Vector3d* nearest = map.FindNearest(Eigen::Vector3d(2.1, 0.25, 0.0), 0.5);
        ASSERT_NE(nearest, nullptr);
        const Eigen::Vector3d* normal = map.NormalOf(nearest);
        if (!in_plane) {
            EXPECT_EQ(normal, nullptr);
            continue;
        }
        ASSERT_NE(normal, nullptr);
        EXPECT_NEAR(std::abs(normal->x()), 1.0, 1e-2);
        EXPECT_EQ(normal->z(), 0.0);
    }
}

TEST(PointToPlane, PlanarPointToLineRegistersARotatedCorridor) {
    // A corridor's two walls and an end wall, sampled 4 cm apart in the map and 15 cm in the scan; the
    // scan is turned by 0.5 deg and shifted 5 cm. Point-to-line in planar mode recovers the pose.
    std::vector<Eigen::Vector3d> map_points, scan_points;
    for (double x = -6.0; x <= 6.0; x += 0.04) {
        map_points.emplace_back(x, 1.2, 0.0);
        map_points.emplace_back(x, -1.2, 0.0);
    }
    for (double y = -1.2; y <= 1.2; y += 0.04) map_points.emplace_back(6.0, y, 0.0);
    const Eigen::Isometry3d truth = PoseFromXYZRPY(0.05, -0.03, 0.0, 0.0, 0.0, 0.5 * kDeg);
    for (double x = -5.0; x <= 5.0; x += 0.15) {
        scan_points.push_back(truth.inverse() * Eigen::Vector3d(x + 0.01, 1.2, 0.0));
        scan_points.push_back(truth.inverse() * Eigen::Vector3d(x + 0.07, -1.2, 0.0));
    }
    for (double y = -1.1; y <= 1.1; y += 0.15) scan_points.push_back(truth.inverse() * Eigen::Vector3d(6.0, y + 0.02, 0.0));
    VoxelHashMap map(0.2, 20);
    map.EnableNormals(true, true);
    map.AddPoints(map_points);
    IcpParams params;
    params.max_correspondence_distance = 0.5;
    params.kernel = 0.1;
    params.planar = true;
    params.point_to_plane = true;
    const IcpResult result = RegisterPointsToMap(scan_points, map, Eigen::Isometry3d::Identity(), params);
    ASSERT_TRUE(result.valid);
    EXPECT_GT(result.plane_correspondences, scan_points.size() / 2);
    const Eigen::Isometry3d error = truth.inverse() * result.T_world_sensor;
    EXPECT_LT(error.translation().norm(), 0.01);
    EXPECT_LT(std::abs(std::atan2(error.linear()(1, 0), error.linear()(0, 0))), 0.02 * kDeg);
}

}  // namespace
}  // namespace revisit
