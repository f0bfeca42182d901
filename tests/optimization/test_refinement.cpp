#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <array>
#include <filesystem>
#include <random>
#include <tuple>
#include <utility>

#include "core/error.hpp"
#include "core/se3.hpp"
#include "optimization/point_grid.hpp"
#include "optimization/smear_gate.hpp"
#include "optimization/refinement.hpp"
#include "optimization/cloud_fixtures.hpp"

namespace revisit {
namespace {

double Degrees(double value) { return value * M_PI / 180.0; }

/// Translation [m] and rotation [deg] between two poses.
std::pair<double, double> PoseError(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
    const Eigen::Isometry3d delta = a.inverse() * b;
    return {delta.translation().norm(), RotationAngle(delta) * 180.0 / M_PI};
}

/// The perturbation of the issue: 0.5 m, 2 degrees, about a tilted axis.
Eigen::Isometry3d IssuePerturbation() {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = Eigen::AngleAxisd(Degrees(2.0), Eigen::Vector3d(0.2, -0.3, 1.0).normalized()).toRotationMatrix();
    T.translation() = Eigen::Vector3d(0.3, -0.35, 0.2).normalized() * 0.5;
    return T;
}

TEST(RefineAlignment, RecoversKnownPerturbationOfRealKittiMap) {
    const auto folder = testing::Kitti00First16();
    if (!std::filesystem::exists(REVISIT_SHARED_DIR) || !std::filesystem::exists(folder / "velodyne/000000.bin"))
        GTEST_SKIP() << "shared KITTI data not present at " << folder;
    const auto scan = testing::ReadKittiBin(folder / "velodyne/000000.bin");
    ASSERT_GT(scan.size(), 100000u);
    // Two disjoint samplings of the same real map, so no point is matched to itself.
    const auto ref_points = testing::Subsample(scan, 2, 0);
    const Eigen::Isometry3d T_query_ref_true = PoseFromXYZRPY(15.0, -4.0, 0.3, Degrees(1.0), Degrees(-0.5), Degrees(35.0));
    const auto query_points = testing::Transform(T_query_ref_true, testing::Subsample(scan, 2, 1));
    const Eigen::Isometry3d guess = T_query_ref_true * IssuePerturbation();
    const auto [guess_m, guess_deg] = PoseError(guess, T_query_ref_true);
    ASSERT_NEAR(guess_m, 0.5, 1e-9);
    ASSERT_NEAR(guess_deg, 2.0, 1e-9);

    const auto result = RefineAlignment(ref_points, query_points, guess, RefinementConfig{});
    const auto [error_m, error_deg] = PoseError(result.T_query_ref, T_query_ref_true);
    EXPECT_LT(error_m, 0.05);
    EXPECT_LT(error_deg, 0.1);
    EXPECT_TRUE(result.accepted) << result.reason;
    EXPECT_TRUE(result.converged);
    EXPECT_GT(result.overlap, 0.8);
    EXPECT_LT(result.rms, 0.2);  // sparse far rings and foliage: ~0.14 m at the true pose
    EXPECT_GT(result.num_correspondences, 5000);
    // A real street constrains every direction: the information is positive definite.
    EXPECT_GT(Eigen::SelfAdjointEigenSolver<Matrix6d>(result.information).eigenvalues()(0), 0.0);
}

/// Uneven ground with low clutter (kerbs, bushes, cars: nothing taller than 1.5 m), points every 0.2 m.
std::vector<Eigen::Vector3d> CourtyardWithLowClutter() {
    std::vector<Eigen::Vector3d> points;
    const auto ground = [](double x, double y) { return 0.3 * std::sin(0.2 * x) + 0.2 * std::cos(0.3 * y); };
    for (double x = -20.0; x <= 20.0; x += 0.2)
        for (double y = -20.0; y <= 20.0; y += 0.2) points.emplace_back(x, y, ground(x, y));
    // Boxes of 1-1.5 m at irregular places and sizes: their sides and tops.
    for (int k = 0; k < 12; ++k) {
        const double cx = -16.0 + 2.7 * k, cy = 9.0 * std::sin(1.7 * k), sx = 0.8 + 0.15 * (k % 4), sy = 1.5 - 0.1 * (k % 5);
        const double top = 1.0 + 0.05 * (k % 11);
        for (double z = 0.0; z <= top; z += 0.2)
            for (double t = -1.0; t <= 1.0; t += 0.05) {
                points.emplace_back(cx + t * sx, cy - sy, ground(cx, cy) + z);
                points.emplace_back(cx + t * sx, cy + sy, ground(cx, cy) + z);
                points.emplace_back(cx - sx, cy + t * sy, ground(cx, cy) + z);
                points.emplace_back(cx + sx, cy + t * sy, ground(cx, cy) + z);
            }
        for (double u = -1.0; u <= 1.0; u += 0.1)
            for (double w = -1.0; w <= 1.0; w += 0.1) points.emplace_back(cx + u * sx, cy + w * sy, ground(cx, cy) + top);
    }
    return points;
}

/// A 2D closure knows x, y and yaw; its height comes from the maps' ground planes, which were 3.3 m
/// off on the real Livox walk (a tilted handheld sensor over uneven ground). The vertical search
/// finds the height before ICP, whose gate (2 m) cannot reach it when nothing is taller than 1.5 m.
TEST(RefineAlignment, VerticalSearchRecoversAHeightTheGroundPlanesGotWrong) {
    const auto scene = CourtyardWithLowClutter();
    const auto ref_points = testing::Subsample(scene, 2, 0);
    // The query frame is tilted (a handheld sensor): "up" is not its z axis.
    const Eigen::Isometry3d T_query_ref_true = PoseFromXYZRPY(6.0, 2.0, 0.5, Degrees(12.0), Degrees(-8.0), Degrees(20.0));
    const auto query_points = testing::Transform(T_query_ref_true, testing::Subsample(scene, 2, 1));
    const Eigen::Vector3d up_in_query = T_query_ref_true.linear() * Eigen::Vector3d::UnitZ();
    Eigen::Isometry3d guess = T_query_ref_true;
    guess.translation() -= 3.3 * up_in_query;

    RefinementConfig without;
    without.vertical_search = 0.0;
    const auto lost = RefineAlignment(ref_points, query_points, guess, without, up_in_query);
    EXPECT_GT(PoseError(lost.T_query_ref, T_query_ref_true).first, 1.0);
    EXPECT_FALSE(lost.accepted);

    const auto found = RefineAlignment(ref_points, query_points, guess, RefinementConfig{}, up_in_query);
    const auto [error_m, error_deg] = PoseError(found.T_query_ref, T_query_ref_true);
    EXPECT_LT(error_m, 0.1);  // from 3.3 m; a smooth ground leaves little to pin x, y
    EXPECT_LT(error_deg, 0.2);
    EXPECT_TRUE(found.accepted) << found.reason;
}

TEST(RefineAlignment, RecoversKnownPerturbationOfSyntheticStreet) {
    const auto street = testing::SyntheticStreet(100.0, 20.0, 3);
    const auto ref_points = testing::Subsample(street, 2, 0);
    const Eigen::Isometry3d T_query_ref_true = PoseFromXYZRPY(-20.0, 3.0, 0.0, 0.0, 0.0, Degrees(-60.0));
    const auto query_points = testing::Transform(T_query_ref_true, testing::Subsample(street, 2, 1));
    const auto result = RefineAlignment(ref_points, query_points, T_query_ref_true * IssuePerturbation(), RefinementConfig{});
    const auto [error_m, error_deg] = PoseError(result.T_query_ref, T_query_ref_true);
    EXPECT_LT(error_m, 0.05);
    EXPECT_LT(error_deg, 0.1);
    EXPECT_TRUE(result.accepted) << result.reason;
}

/// `points` with isotropic Gaussian noise of `sigma` metres added.
std::vector<Eigen::Vector3d> WithNoise(std::vector<Eigen::Vector3d> points, double sigma, std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::normal_distribution<double> noise(0.0, sigma);
    for (auto& p : points) p += Eigen::Vector3d(noise(rng), noise(rng), noise(rng));
    return points;
}

TEST(RefineAlignment, InformationFallsWithTheResidualSpread) {
    // The pose graph weighs a closure by its registration (graph.closure_information_from_registration):
    // the same place registered from noisier points must count for less, as 1 / rms^2.
    const auto street = testing::SyntheticStreet(100.0, 20.0, 3);
    const auto ref_points = testing::Subsample(street, 2, 0);
    const Eigen::Isometry3d T_query_ref_true = PoseFromXYZRPY(-20.0, 3.0, 0.0, 0.0, 0.0, Degrees(-60.0));
    const auto clean = testing::Transform(T_query_ref_true, testing::Subsample(street, 2, 1));
    const auto sharp = RefineAlignment(ref_points, WithNoise(clean, 0.03, 1), T_query_ref_true, RefinementConfig{});
    const auto blurred = RefineAlignment(ref_points, WithNoise(clean, 0.09, 2), T_query_ref_true, RefinementConfig{});
    ASSERT_TRUE(sharp.accepted) << sharp.reason;
    ASSERT_TRUE(blurred.accepted) << blurred.reason;
    ASSERT_GT(blurred.rms, 1.5 * sharp.rms);
    const double expected = (sharp.rms * sharp.rms) / (blurred.rms * blurred.rms);
    EXPECT_NEAR(blurred.information.trace() / sharp.information.trace(), expected, 0.2 * expected);
    // Each direction, not only the sum: the translation along the street as well as across it.
    for (int axis = 0; axis < 6; ++axis)
        EXPECT_LT(blurred.information(axis, axis), 0.8 * sharp.information(axis, axis)) << axis;
}

/// A 2D laser's local map: the walls of a 20 x 12 m floor with rooms off a corridor, every point
/// at z = 0, a point every `spacing` metres with 1 cm noise.
std::vector<Eigen::Vector3d> PlanarFloor(double spacing, std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::normal_distribution<double> noise(0.0, 0.01);
    const std::vector<std::array<double, 4>> walls = {
        {0, 0, 20, 0}, {0, 12, 20, 12}, {0, 0, 0, 12}, {20, 0, 20, 12},  // outline
        {0, 5, 8, 5}, {9.5, 5, 20, 5}, {0, 7, 14, 7}, {15.5, 7, 20, 7},  // corridor with doors
        {6, 0, 6, 5}, {13, 0, 13, 5}, {4, 7, 4, 12}, {11, 7, 11, 12}, {17, 7, 17, 12}};  // rooms
    std::vector<Eigen::Vector3d> points;
    for (const auto& w : walls) {
        const Eigen::Vector2d a(w[0], w[1]), b(w[2], w[3]);
        const int steps = static_cast<int>((b - a).norm() / spacing);
        for (int i = 0; i <= steps; ++i) {
            const Eigen::Vector2d p = a + (b - a) * (double(i) / steps);
            points.emplace_back(p.x() + noise(rng), p.y() + noise(rng), 0.0);
        }
    }
    return points;
}

/// The 2D laser proportions of the data-derived settings (0.05 m voxels).
RefinementConfig PlanarLaserConfig() {
    RefinementConfig config;
    config.voxel_size = 0.1;
    config.normal_radius = 0.3;
    config.initial_max_distance = 1.0;
    config.max_correspondence_distance = 0.3;
    config.max_rms = 0.1;
    config.min_correspondences = 50;
    return config;
}

TEST(RefineAlignment, RegistersPlanarMapsInThePlane) {
    // Two samplings of one floor, 0.3 m and 3 deg apart: a wall's 3D neighbourhood is a line whose
    // smallest eigenvector may be the vertical; the planar normals must still pull x, y and yaw.
    const RefinementConfig config = PlanarLaserConfig();
    const auto ref_points = PlanarFloor(0.02, 1);
    const Eigen::Isometry3d T_query_ref_true = PoseFromXYZRPY(3.0, -2.0, 0.0, 0.0, 0.0, Degrees(25.0));
    const auto query_points = testing::Transform(T_query_ref_true, PlanarFloor(0.02, 2));
    const Eigen::Isometry3d guess = T_query_ref_true * PoseFromXYZRPY(0.25, -0.15, 0.0, 0.0, 0.0, Degrees(3.0));
    const auto result = RefineAlignment(ref_points, query_points, guess, config);
    const auto [error_m, error_deg] = PoseError(result.T_query_ref, T_query_ref_true);
    EXPECT_LT(error_m, 0.03);  // from 0.29 m
    EXPECT_LT(error_deg, 0.2);  // from 3 deg
    EXPECT_NEAR(result.T_query_ref.translation().z(), 0.0, 1e-6);
    EXPECT_TRUE(result.accepted) << result.reason;
    EXPECT_LT(result.rms, 0.03);
    EXPECT_GT(result.rms, 0.0);  // the in-plane distances are measured (a vertical normal measures 0)
}

/// The proximity pass prepares a query map once for several references: the same results, bit for bit,
/// for 3D maps and for a 2D laser's (whose planes are taken in the plane only when both maps are flat).
TEST(RefineAlignment, APreparedQueryMapGivesTheSameResults) {
    const auto street = testing::SyntheticStreet(100.0, 20.0, 3);
    const Eigen::Isometry3d T_street = PoseFromXYZRPY(-20.0, 3.0, 0.0, 0.0, 0.0, Degrees(-60.0));
    const auto street_query = testing::Transform(T_street, testing::Subsample(street, 2, 1));
    const RefinementConfig planar_config = PlanarLaserConfig();
    const Eigen::Isometry3d T_floor = PoseFromXYZRPY(3.0, -2.0, 0.0, 0.0, 0.0, Degrees(25.0));
    const auto floor_query = testing::Transform(T_floor, PlanarFloor(0.02, 2));
    auto lifted = PlanarFloor(0.02, 1);  // the same floor, but not flat: a 3D reference onto a flat query
    for (std::size_t i = 0; i < lifted.size(); i += 7) lifted[i].z() += 0.5;
    struct Case {
        std::vector<Eigen::Vector3d> ref, query;
        Eigen::Isometry3d guess;
        RefinementConfig config;
    };
    const std::vector<Case> cases = {
        {testing::Subsample(street, 2, 0), street_query, T_street * IssuePerturbation(), RefinementConfig{}},
        {PlanarFloor(0.02, 1), floor_query, T_floor * PoseFromXYZRPY(0.25, -0.15, 0.0, 0.0, 0.0, Degrees(3.0)), planar_config},
        {lifted, floor_query, T_floor * PoseFromXYZRPY(0.25, -0.15, 0.0, 0.0, 0.0, Degrees(3.0)), planar_config}};
    for (std::size_t k = 0; k < cases.size(); ++k) {
        const Case& c = cases[k];
        const RefinementResult plain = RefineAlignment(c.ref, c.query, c.guess, c.config);
        const RefinementQuery prepared(c.query, c.config);
        EXPECT_EQ(prepared.planar(), k > 0) << "case " << k;
        const RefinementResult reused = RefineAlignment(c.ref, prepared, c.guess, c.config);
        EXPECT_TRUE(plain.T_query_ref.matrix() == reused.T_query_ref.matrix()) << "case " << k;
        EXPECT_EQ(plain.overlap, reused.overlap) << "case " << k;
        EXPECT_EQ(plain.rms, reused.rms) << "case " << k;
        EXPECT_EQ(plain.num_correspondences, reused.num_correspondences) << "case " << k;
        EXPECT_EQ(plain.accepted, reused.accepted) << "case " << k;
        EXPECT_EQ(plain.reason, reused.reason) << "case " << k;
        // Keeping the grids of the planes: the second registration reads them, with the same results.
        RefinementQuery kept(c.query, c.config);
        kept.KeepPlaneGrids();
        for (int pass = 0; pass < 2; ++pass) {
            const RefinementResult again = RefineAlignment(c.ref, kept, c.guess, c.config);
            EXPECT_TRUE(plain.T_query_ref.matrix() == again.T_query_ref.matrix()) << "case " << k << " pass " << pass;
            EXPECT_EQ(plain.num_correspondences, again.num_correspondences) << "case " << k << " pass " << pass;
            EXPECT_EQ(plain.overlap, again.overlap) << "case " << k << " pass " << pass;
        }
    }
    EXPECT_TRUE(RefineAlignment(cases[0].ref, cases[0].query, cases[0].guess, cases[0].config).accepted);
    RefinementConfig other = cases[0].config;
    other.normal_radius = 2.0;
    EXPECT_THROW(RefineAlignment(cases[0].ref, RefinementQuery(cases[0].query, cases[0].config), cases[0].guess, other), ConfigError);
}

/// A map's planes prepared under its levelled vertical serve its registration onto its predecessor
/// (under z, without a vertical search) where they are the same planes: a 3D map. A 2D laser's map
/// lies at one height, where the vertical decides its planes.
TEST(RegisterConsecutive, APreparedQueryMapGivesTheSameResultWhereItsPlanesAreTheSame) {
    const auto street = testing::SyntheticStreet(100.0, 20.0, 3);
    const Eigen::Isometry3d T_street = PoseFromXYZRPY(-20.0, 3.0, 0.0, 0.0, 0.0, Degrees(-60.0));
    const auto query = testing::Transform(T_street, testing::Subsample(street, 2, 1));
    const auto ref = testing::Subsample(street, 2, 0);
    const Eigen::Vector3d tilted_up = Eigen::Vector3d(0.02, -0.01, 1.0).normalized();
    const RefinementQuery prepared(query, RefinementConfig{}, tilted_up);
    EXPECT_TRUE(prepared.SamePlanesAs(Eigen::Vector3d::UnitZ()));
    const RefinementResult plain = RegisterConsecutive(ref, query, T_street * IssuePerturbation(), RefinementConfig{});
    const RefinementResult reused = RegisterConsecutive(ref, prepared, T_street * IssuePerturbation(), RefinementConfig{});
    EXPECT_TRUE(plain.T_query_ref.matrix() == reused.T_query_ref.matrix());
    EXPECT_EQ(plain.rms, reused.rms);
    EXPECT_EQ(plain.overlap, reused.overlap);
    EXPECT_EQ(plain.num_correspondences, reused.num_correspondences);
    // A flat map: planes in the plane orthogonal to its own vertical only.
    const auto floor = PlanarFloor(0.02, 2);
    const RefinementQuery flat(floor, PlanarLaserConfig());
    EXPECT_TRUE(flat.planar());
    EXPECT_TRUE(flat.SamePlanesAs(Eigen::Vector3d::UnitZ()));
    EXPECT_TRUE(flat.SamePlanesAs(2.0 * Eigen::Vector3d::UnitZ()));
    EXPECT_FALSE(flat.SamePlanesAs(tilted_up));
    EXPECT_FALSE(RefinementQuery(floor, PlanarLaserConfig(), tilted_up).SamePlanesAs(Eigen::Vector3d::UnitZ()));
}

TEST(RefineAlignment, GivesTheSameResultWithOneThread) {
    const auto street = testing::SyntheticStreet(60.0, 10.0, 5);
    const auto ref_points = testing::Subsample(street, 2, 0);
    const Eigen::Isometry3d T_query_ref_true = PoseFromXYZRPY(5.0, 1.0, 0.0, 0.0, 0.0, Degrees(10.0));
    const auto query_points = testing::Transform(T_query_ref_true, testing::Subsample(street, 2, 1));
    const Eigen::Isometry3d guess = T_query_ref_true * IssuePerturbation();
    const auto parallel = RefineAlignment(ref_points, query_points, guess, RefinementConfig{});
    const tbb::global_control one_thread(tbb::global_control::max_allowed_parallelism, 1);
    const auto serial = RefineAlignment(ref_points, query_points, guess, RefinementConfig{});
    EXPECT_TRUE(serial.T_query_ref.isApprox(parallel.T_query_ref, 1e-9));
    EXPECT_EQ(serial.num_correspondences, parallel.num_correspondences);
    EXPECT_EQ(serial.iterations, parallel.iterations);
}

TEST(RefineAlignment, RejectsWrongPlaceWithReason) {
    // Two different streets (different seeds) presented as a closure: ICP finds some local
    // fit, but the maps do not overlap once aligned.
    const auto ref_points = testing::SyntheticStreet(100.0, 10.0, 3);
    const auto query_points = testing::SyntheticStreet(100.0, 10.0, 11);
    const Eigen::Isometry3d guess = PoseFromXYZRPY(0.0, 0.0, 0.0, 0.0, 0.0, Degrees(90.0));
    const auto result = RefineAlignment(ref_points, query_points, guess, RefinementConfig{});
    EXPECT_FALSE(result.accepted);
    EXPECT_FALSE(result.reason.empty());
    EXPECT_LT(result.overlap, RefinementConfig{}.min_overlap);
}

TEST(RefineAlignment, RejectsEmptyMap) {
    const auto street = testing::SyntheticStreet(20.0, 5.0, 1);
    const auto result = RefineAlignment({}, street, Eigen::Isometry3d::Identity(), RefinementConfig{});
    EXPECT_FALSE(result.accepted);
    EXPECT_EQ(result.reason, "empty map");
    EXPECT_EQ(result.num_correspondences, 0);
}

TEST(RefineAlignment, RejectsInvalidConfig) {
    RefinementConfig config;
    config.initial_max_distance = 0.5;  // below the final gate
    EXPECT_THROW(RefineAlignment({{0, 0, 0}}, {{0, 0, 0}}, Eigen::Isometry3d::Identity(), config), ConfigError);
}

TEST(VoxelOverlap, CountsSharedVoxelsOfTheSmallerCloud) {
    const std::vector<Eigen::Vector3d> a = {{0.1, 0.1, 0.1}, {1.1, 0.1, 0.1}, {2.1, 0.1, 0.1}, {3.1, 0.1, 0.1}};
    const std::vector<Eigen::Vector3d> b = {{0.2, 0.2, 0.2}, {5.5, 0.1, 0.1}};
    EXPECT_DOUBLE_EQ(VoxelOverlap(a, b, 1.0), 0.5);
    EXPECT_DOUBLE_EQ(VoxelOverlap(a, {}, 1.0), 0.0);
    EXPECT_EQ(VoxelDownsample(a, 10.0).size(), 1u);
}

TEST(PointGrid, FindsTheNearestPointBeyondOneCell) {
    const std::vector<Eigen::Vector3d> points = {{0, 0, 0}, {2.5, 0, 0}, {0, 0.4, 0}};
    const PointGrid grid(points, 0.5);
    EXPECT_EQ(grid.FindNearest({0, 0.3, 0}, 0.5), 2);
    EXPECT_EQ(grid.FindNearest({2.0, 0, 0}, 0.4), -1);
    EXPECT_EQ(grid.FindNearest({2.0, 0, 0}, 0.6), 1);
    EXPECT_EQ(grid.FindWithin({0, 0, 0}, 0.45).size(), 2u);
}

// The search starts at the query's own cell, skips cells whose box lies beyond the best point so far
// and empty cells by their occupancy bit; it must still answer what a visit of every neighbour cell in
// (dx, dy, dz) order answers, ties included: points snapped to a lattice (as the run folder's map
// points are) lie at exactly equal distances, and that visit keeps the last of them.
TEST(PointGrid, FindsWhatAVisitOfEveryNeighbourCellFinds) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> uniform(-3.0, 3.0);
    std::vector<Eigen::Vector3d> near;
    for (int i = 0; i < 600; ++i) near.emplace_back(uniform(rng), uniform(rng), uniform(rng));
    for (int i = 0; i < 600; ++i)  // a 0.25 m lattice: many exactly equidistant pairs
        near.push_back(0.25 * Eigen::Vector3d(std::round(4 * uniform(rng)), std::round(4 * uniform(rng)), std::round(uniform(rng))));
    // With a far point the cells' bounding box is too large for the occupancy bits: every cell is looked up.
    std::vector<Eigen::Vector3d> with_far_point = near;
    with_far_point.emplace_back(4000.0, -3000.0, 2500.0);
    for (const auto& [cell, points] : {std::pair{0.5, &near}, std::pair{0.9, &near}, std::pair{0.9, &with_far_point}}) {
        const PointGrid grid(*points, cell);
        for (const double max_distance : {0.4, cell, 2.0 * cell + 0.1}) {
            const int reach = int(std::ceil(max_distance / cell));
            int ties = 0;
            for (int q = 0; q < 3000; ++q) {
                // Queries on the lattice too (equal distances to its neighbours) and on cell borders.
                Eigen::Vector3d query(uniform(rng), uniform(rng), uniform(rng));
                if (q % 3 == 1) query = 0.125 * (query * 8.0).array().round().matrix();
                if (q % 3 == 2) query = cell * (query / cell).array().round().matrix();
                // Every point, in the full visit's order: its cell's place among the neighbours, then its index.
                const Eigen::Vector3i center = VoxelOf(query, cell);
                int expected = -1;
                std::tuple<double, int, int> best{max_distance * max_distance, -1, -1};
                for (int i = 0; i < int(points->size()); ++i) {
                    const Eigen::Vector3i d = VoxelOf((*points)[std::size_t(i)], cell) - center;
                    if (d.cwiseAbs().maxCoeff() > reach) continue;
                    const double squared = ((*points)[std::size_t(i)] - query).squaredNorm();
                    const int rank = ((d.x() + reach) * (2 * reach + 1) + d.y() + reach) * (2 * reach + 1) + d.z() + reach;
                    if (squared > std::get<0>(best)) continue;
                    if (squared == std::get<0>(best) && std::make_pair(rank, i) < std::make_pair(std::get<1>(best), std::get<2>(best))) {
                        ++ties;
                        continue;
                    }
                    ties += squared == std::get<0>(best) && expected >= 0;
                    best = {squared, rank, i};
                    expected = i;
                }
                ASSERT_EQ(grid.FindNearest(query, max_distance), expected) << "cell " << cell << " query " << query.transpose();
            }
            EXPECT_GT(ties, 0) << "the queries should meet equidistant points";
        }
    }
}

TEST(PointGrid, SparsePointsAnswerLikeBruteForceAroundAndBeyondTheirBox) {
    // Few points far apart: most queries have no occupied cell around them (answered from the bits
    // of the cells near an occupied one), others lie just beside a point in any of the 26 directions
    // or outside the points' box.
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> uniform(-20.0, 20.0), nearby(-1.2, 1.2);
    std::vector<Eigen::Vector3d> points;
    for (int i = 0; i < 40; ++i) points.emplace_back(uniform(rng), uniform(rng), 0.25 * uniform(rng));
    for (const double cell : {0.9, 1.0}) {
        const PointGrid grid(points, cell);
        int found = 0, empty = 0;
        for (int q = 0; q < 20000; ++q) {
            Eigen::Vector3d query = q % 2 ? Eigen::Vector3d(uniform(rng), uniform(rng), uniform(rng))
                                          : Eigen::Vector3d(points[std::size_t(q / 2) % points.size()] +
                                                            Eigen::Vector3d(nearby(rng), nearby(rng), nearby(rng)));
            int expected = -1;
            double best = cell * cell;
            for (int i = 0; i < int(points.size()); ++i) {
                const double squared = (points[std::size_t(i)] - query).squaredNorm();
                if (squared <= best) best = squared, expected = i;  // no ties among random points
            }
            ASSERT_EQ(grid.FindNearest(query, cell), expected) << "cell " << cell << " query " << query.transpose();
            (expected >= 0 ? found : empty) += 1;
        }
        EXPECT_GT(found, 1000);
        EXPECT_GT(empty, 2000);
    }
}

}  // namespace
}  // namespace revisit
