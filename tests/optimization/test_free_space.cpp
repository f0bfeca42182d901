// The free-space check of 2D pairs (optimization/free_space.hpp): what a map saw through is evidence.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "optimization/free_space.hpp"

namespace revisit {
namespace {

/// A rectangular room [0, 12] x [0, 6] m with a 2 m square pillar at (7, 2)-(9, 4): the returns of a
/// 360-beam laser at `T_world_scan`, in its sensor frame.
std::vector<Eigen::Vector3f> ScanRoom(const Eigen::Isometry3d& T_world_scan) {
    struct Segment {
        Eigen::Vector2d a, b;
    };
    const std::vector<Segment> walls = {{{0, 0}, {12, 0}}, {{12, 0}, {12, 6}}, {{12, 6}, {0, 6}}, {{0, 6}, {0, 0}},
                                        {{7, 2}, {9, 2}},  {{9, 2}, {9, 4}},   {{9, 4}, {7, 4}},   {{7, 4}, {7, 2}}};
    const Eigen::Vector2d origin = T_world_scan.translation().head<2>();
    const Eigen::Isometry3d T_scan_world = T_world_scan.inverse();
    std::vector<Eigen::Vector3f> points;
    for (int beam = 0; beam < 360; ++beam) {
        const double angle = beam * M_PI / 180.0;
        const Eigen::Vector2d d(std::cos(angle), std::sin(angle));
        double nearest = 1e9;
        for (const auto& w : walls) {
            const Eigen::Vector2d e = w.b - w.a;
            const double denom = d.x() * e.y() - d.y() * e.x();
            if (std::abs(denom) < 1e-12) continue;
            const Eigen::Vector2d r = w.a - origin;
            const double t = (r.x() * e.y() - r.y() * e.x()) / denom;
            const double s = (r.x() * d.y() - r.y() * d.x()) / denom;
            if (t > 0 && s >= 0 && s <= 1) nearest = std::min(nearest, t);
        }
        if (nearest > 30) continue;
        const Eigen::Vector3d hit(origin.x() + nearest * d.x(), origin.y() + nearest * d.y(), 0.0);
        points.push_back((T_scan_world * hit).cast<float>());
    }
    return points;
}

Eigen::Isometry3d Pose(double x, double y, double yaw) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    T.translation() = Eigen::Vector3d(x, y, 0);
    return T;
}

/// A map of scans taken at `T_world_scans`, its frame at the first of them.
ObservedGrid MapFrom(const std::vector<Eigen::Isometry3d>& T_world_scans, Eigen::Isometry3d* T_world_map) {
    *T_world_map = T_world_scans.front();
    std::vector<std::vector<Eigen::Vector3f>> scans;
    std::vector<Eigen::Isometry3d> T_map_scan;
    for (const auto& T : T_world_scans) {
        scans.push_back(ScanRoom(T));
        T_map_scan.push_back(T_world_map->inverse() * T);
    }
    return ObservedGrid(scans, T_map_scan, 0.2, 0.4);
}

TEST(FreeSpace, TheTrueAlignmentAgreesAndAShiftedOnePutsWallsWhereTheOtherMapSawThrough) {
    Eigen::Isometry3d T_world_a, T_world_b;
    // Map a walks along the room's south side, map b comes back along its north side, turned around.
    const ObservedGrid a = MapFrom({Pose(1.5, 1.0, 0.0), Pose(3.0, 1.2, 0.1), Pose(5.0, 1.0, 0.0)}, &T_world_a);
    const ObservedGrid b = MapFrom({Pose(11.0, 5.0, 3.1), Pose(9.5, 5.2, 3.0), Pose(8.0, 5.0, 3.2)}, &T_world_b);
    const Eigen::Isometry3d T_a_b = T_world_a.inverse() * T_world_b;

    const auto b_in_a = Agreement(a, b, T_a_b);
    const auto a_in_b = Agreement(b, a, T_a_b.inverse());
    EXPECT_GT(b_in_a.observed(), 100);
    EXPECT_GT(a_in_b.observed(), 100);
    EXPECT_GE(b_in_a.ratio(), 0.95);
    EXPECT_GE(a_in_b.ratio(), 0.95);

    // The same pair 1 m along the room, or turned by 5 deg: b's pillar and walls land in a's free space.
    for (const auto& error : {Pose(1.0, 0.0, 0.0), Pose(0.0, 0.6, 0.0), Pose(0.0, 0.0, 5.0 * M_PI / 180.0)}) {
        const Eigen::Isometry3d T_wrong = error * T_a_b;
        const auto wrong = Agreement(a, b, T_wrong);
        const auto wrong_back = Agreement(b, a, T_wrong.inverse());
        EXPECT_LT(std::min(wrong.ratio(), wrong_back.ratio()), 0.85) << error.translation().transpose();
        EXPECT_GT(wrong.contradict + wrong_back.contradict, 20);
    }
}

TEST(FreeSpace, MapsThatSawNothingInCommonHaveNoEvidence) {
    Eigen::Isometry3d T_world_a, T_world_b;
    const ObservedGrid a = MapFrom({Pose(1.5, 1.0, 0.0)}, &T_world_a);
    const ObservedGrid b = MapFrom({Pose(11.0, 5.0, 3.1)}, &T_world_b);
    // b placed 100 m away: none of its walls falls where a looked.
    const auto far = Agreement(a, b, Pose(100.0, 0.0, 0.0) * (T_world_a.inverse() * T_world_b));
    EXPECT_EQ(far.observed(), 0);
    EXPECT_EQ(far.ratio(), 0.0);
    EXPECT_TRUE(ObservedGrid().empty());
    EXPECT_EQ(Agreement(ObservedGrid(), b, Eigen::Isometry3d::Identity()).observed(), 0);
}

TEST(FreeSpace, AReturnMakesItsCellOccupiedEvenWhereAnotherBeamPassedThrough) {
    // Two scans of one map: the second sees the pillar's west face, which the first one's beams along the
    // room's south side never cross; every occupied cell must stay occupied, never free.
    Eigen::Isometry3d T_world_a;
    const ObservedGrid a = MapFrom({Pose(1.0, 3.0, 0.0), Pose(1.0, 1.0, 0.0)}, &T_world_a);
    for (const auto& centre : a.occupied_centres()) {
        const auto cell = a.CellOf(centre);
        EXPECT_TRUE(a.Occupied(cell));
        EXPECT_FALSE(a.Free(cell));
    }
    // The room's centre, between the sensors and the pillar, is free.
    const Eigen::Vector3d centre_in_map = T_world_a.inverse() * Eigen::Vector3d(4.0, 3.0, 0.0);
    EXPECT_TRUE(a.Free(a.CellOf(centre_in_map.head<2>())));
}

}  // namespace
}  // namespace revisit
