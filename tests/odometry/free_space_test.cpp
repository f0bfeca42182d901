// Where a 2D laser's beams passed, and what a scan placed at a pose contradicts (odometry/free_space).
#include "odometry/free_space.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace revisit {
namespace {

/// Returns of a 181-beam, 180-deg laser at `T_world_sensor` inside the axis-aligned room
/// [-w, w] x [-h, h] (sensor frame).
std::vector<Eigen::Vector3d> ScanOfRoom(const Eigen::Isometry3d& T_world_sensor, double w, double h) {
    std::vector<Eigen::Vector3d> returns;
    const Eigen::Vector2d origin = T_world_sensor.translation().head<2>();
    for (int beam = 0; beam <= 180; ++beam) {
        const double angle = (beam - 90) * M_PI / 180.0;
        const Eigen::Vector2d direction = (T_world_sensor.linear() * Eigen::Vector3d(std::cos(angle), std::sin(angle), 0.0)).head<2>();
        double reach = 1e9;  // the nearest wall along the beam
        for (int axis = 0; axis < 2; ++axis) {
            const double limit = axis == 0 ? w : h;
            if (std::abs(direction[axis]) < 1e-12) continue;
            const double wall = direction[axis] > 0.0 ? limit : -limit;
            reach = std::min(reach, (wall - origin[axis]) / direction[axis]);
        }
        const Eigen::Vector3d end_in_world(origin.x() + reach * direction.x(), origin.y() + reach * direction.y(), 0.0);
        returns.push_back(T_world_sensor.inverse() * end_in_world);
    }
    return returns;
}

Eigen::Isometry3d Pose(double x, double y, double yaw_deg) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = Eigen::AngleAxisd(yaw_deg * M_PI / 180.0, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    T.translation() = Eigen::Vector3d(x, y, 0.0);
    return T;
}

std::vector<Eigen::Vector3d> InWorld(const Eigen::Isometry3d& T, const std::vector<Eigen::Vector3d>& points) {
    std::vector<Eigen::Vector3d> out;
    for (const auto& p : points) out.push_back(T * p);
    return out;
}

TEST(FreeSpace2D, AScanAtItsPoseContradictsNothingAndTurnedByNinetyDegreesItsBeamsCrossTheWalls) {
    constexpr double kCell = 0.2;
    // A 12 m x 6 m room, mapped from its centre looking both ways (a spin in place).
    FreeSpace2D free(kCell);
    VoxelHashMap map(kCell, 20);
    for (const double yaw : {0.0, 180.0}) {
        const Eigen::Isometry3d T = Pose(0.0, 0.0, yaw);
        const auto returns = InWorld(T, ScanOfRoom(T, 6.0, 3.0));
        free.AddBeams(T.translation(), returns, 2 * kCell);
        map.AddPoints(returns);
    }
    const Eigen::Isometry3d T_true = Pose(0.5, 0.0, 30.0);
    const auto scan = ScanOfRoom(T_true, 6.0, 3.0);
    const BeamConflicts at_true = CountBeamConflicts(free, map, scan, T_true, 2 * kCell);
    EXPECT_LE(at_true.Total(), 3u);
    // Turned by 90 deg, the beams that reached the far walls (6 m) now cross the near ones (3 m), and
    // the returns of the near walls land in the room's crossed middle.
    const BeamConflicts turned = CountBeamConflicts(free, map, scan, Pose(0.5, 0.0, 120.0), 2 * kCell);
    EXPECT_GT(turned.beams_through_walls, 40u);
    EXPECT_GT(turned.returns_in_free, 20u);
    EXPECT_TRUE(ClearlyMore(static_cast<double>(turned.Total()), static_cast<double>(at_true.Total())));
}

TEST(FreeSpace2D, ABeamMarksTheCellsShortOfItsReturnAndFarCellsAreForgotten) {
    FreeSpace2D free(0.2);
    free.AddBeams(Eigen::Vector3d::Zero(), {Eigen::Vector3d(10.0, 0.0, 0.0)}, 0.4);
    EXPECT_TRUE(free.Free(Eigen::Vector3d(0.05, 0.05, 0.0)));
    EXPECT_TRUE(free.Free(Eigen::Vector3d(9.5, 0.05, 0.0)));
    EXPECT_FALSE(free.Free(Eigen::Vector3d(9.7, 0.05, 0.0)));   // the wall's margin
    EXPECT_FALSE(free.Free(Eigen::Vector3d(5.0, 0.3, 0.0)));    // beside the beam
    EXPECT_FALSE(free.Free(Eigen::Vector3d(-1.0, 0.05, 0.0)));  // behind the sensor
    EXPECT_EQ(free.NumCells(), 48u);  // 9.6 m of 0.2 m cells

    // Beams 100 m away: once the set has grown enough to sweep, the cells beyond the radius go.
    for (int i = 0; i < 400; ++i) {
        const Eigen::Vector3d origin(100.0, 0.2 * i, 0.0);
        free.AddBeams(origin, {origin + Eigen::Vector3d(5.0, 0.0, 0.0)}, 0.4);
    }
    free.RemoveFarFrom(Eigen::Vector3d(100.0, 0.0, 0.0), 30.0);
    EXPECT_FALSE(free.Free(Eigen::Vector3d(5.0, 0.05, 0.0)));
    EXPECT_TRUE(free.Free(Eigen::Vector3d(102.0, 0.05, 0.0)));
    EXPECT_FALSE(free.Free(Eigen::Vector3d(102.0, 50.05, 0.0)));  // 50 m from the origin
}

}  // namespace
}  // namespace revisit
