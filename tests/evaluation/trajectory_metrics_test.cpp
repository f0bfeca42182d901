#include "evaluation/trajectory_metrics.hpp"

#include "core/se3.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace revisit {
namespace {

constexpr double kPi = 3.14159265358979323846;

Eigen::Isometry3d Translation(double x, double y, double z) { return PoseFromXYZRPY(x, y, z, 0, 0, 0); }

/// A wiggly 3D route with changing heading, 1 m per pose.
Poses WigglyRoute(std::size_t count) {
    Poses poses;
    for (std::size_t i = 0; i < count; ++i) {
        const double s = static_cast<double>(i);
        poses.push_back(PoseFromXYZRPY(s, 5.0 * std::sin(0.1 * s), 0.5 * std::cos(0.05 * s), 0.02 * std::sin(0.3 * s),
                                       0.01 * s, 0.1 * std::sin(0.1 * s)));
    }
    return poses;
}

TEST(ComputeApe, HandComputedErrorsWithoutAlignment) {
    const Poses reference = {Translation(0, 0, 0), Translation(1, 0, 0), Translation(2, 0, 0), Translation(3, 0, 0)};
    Poses estimate = reference;
    estimate[1] = Translation(1, 0.3, 0.4);                                  // 0.5 m off
    estimate[2] = PoseFromXYZRPY(2, 0, 0, 0, 0, 10.0 * kPi / 180.0);          // 10 degrees off
    const auto ape = ComputeApe(estimate, reference, /*align=*/false);
    ASSERT_EQ(ape.errors.translation.size(), 4u);
    EXPECT_NEAR(ape.errors.translation[1], 0.5, 1e-12);
    EXPECT_NEAR(ape.errors.rotation_deg[2], 10.0, 1e-9);
    EXPECT_NEAR(ape.errors.translation_stats.rmse, std::sqrt(0.25 / 4.0), 1e-12);
    EXPECT_NEAR(ape.errors.translation_stats.mean, 0.125, 1e-12);
    EXPECT_NEAR(ape.errors.translation_stats.max, 0.5, 1e-12);
    EXPECT_NEAR(ape.errors.rotation_deg_stats.mean, 2.5, 1e-9);
}

TEST(ComputeApe, RigidMisalignmentVanishesAfterUmeyama) {
    const Poses reference = WigglyRoute(200);
    const Eigen::Isometry3d T_est_ref = PoseFromXYZRPY(12.0, -40.0, 3.0, 0.1, -0.2, 1.3);
    Poses estimate;
    for (const auto& T : reference) estimate.push_back(T_est_ref * T);
    EXPECT_GT(ComputeApe(estimate, reference, false).errors.translation_stats.rmse, 10.0);
    const auto ape = ComputeApe(estimate, reference, true);
    EXPECT_LT(ape.errors.translation_stats.max, 1e-6);
    EXPECT_LT(ape.errors.rotation_deg_stats.max, 1e-5);
    EXPECT_LT((ape.T_ref_est.matrix() - T_est_ref.inverse().matrix()).norm(), 1e-6);
}

TEST(ComputeApe, AlignmentLeavesOnlyTheNonRigidPart) {
    // Noise on top of a rigid offset: aligned APE equals the APE of the noise alone, roughly, and never more
    // than the unaligned APE of the noisy estimate without the offset (Umeyama minimizes the SSE).
    const Poses reference = WigglyRoute(300);
    std::mt19937 rng(5);
    std::normal_distribution<double> noise(0.0, 0.1);
    Poses noisy;
    for (const auto& T : reference) noisy.push_back(Translation(noise(rng), noise(rng), noise(rng)) * T);
    const double noise_rmse = ComputeApe(noisy, reference, false).errors.translation_stats.rmse;
    Poses estimate;
    const Eigen::Isometry3d offset = PoseFromXYZRPY(-5.0, 2.0, 1.0, 0.0, 0.0, -0.7);
    for (const auto& T : noisy) estimate.push_back(offset * T);
    const double aligned_rmse = ComputeApe(estimate, reference, true).errors.translation_stats.rmse;
    EXPECT_LE(aligned_rmse, noise_rmse + 1e-9);
    EXPECT_GT(aligned_rmse, 0.9 * noise_rmse);
}

TEST(ComputeRpe, ConstantScaleErrorPerStep) {
    Poses reference, estimate;
    for (int i = 0; i < 11; ++i) {
        reference.push_back(Translation(i, 0, 0));
        estimate.push_back(Translation(1.1 * i, 0, 0));
    }
    const auto rpe = ComputeRpe(estimate, reference, 1);
    ASSERT_EQ(rpe.translation.size(), 10u);
    EXPECT_NEAR(rpe.translation_stats.rmse, 0.1, 1e-9);
    EXPECT_NEAR(rpe.rotation_deg_stats.max, 0.0, 1e-9);
    const auto rpe5 = ComputeRpe(estimate, reference, 5);  // pairs (0,5), (5,10)
    ASSERT_EQ(rpe5.translation.size(), 2u);
    EXPECT_NEAR(rpe5.translation_stats.mean, 0.5, 1e-9);
}

TEST(ComputeKittiErrors, OnePercentScaleDrift) {
    // 1 m steps: a segment of length L ends L + 1 frames later (first travel strictly beyond L),
    // so the devkit's error is 0.01 * (L + 1) / L.
    Poses reference, estimate;
    for (int i = 0; i < 1000; ++i) {
        reference.push_back(Translation(i, 0, 0));
        estimate.push_back(Translation(1.01 * i, 0, 0));
    }
    const auto errors = ComputeKittiErrors(estimate, reference);
    ASSERT_EQ(errors.per_length.size(), 8u);
    for (const auto& length : errors.per_length) {
        EXPECT_NEAR(length.translation_percent, (length.length + 1.0) / length.length, 1e-9) << length.length;
        EXPECT_NEAR(length.rotation_deg_per_100m, 0.0, 1e-9);
        // first frames 0, 10, ... with first + L + 1 <= 999.
        EXPECT_EQ(length.num_segments, static_cast<std::size_t>((998 - length.length) / 10) + 1) << length.length;
    }
    EXPECT_GT(errors.translation_percent, 1.0);
    EXPECT_LT(errors.translation_percent, 1.01);
}

TEST(ComputeKittiErrors, RollDriftGivesDegreesPer100m) {
    // Rolling about the travel direction leaves positions unchanged: a pure rotation error.
    Poses reference, estimate;
    for (int i = 0; i < 300; ++i) {
        reference.push_back(Translation(i, 0, 0));
        estimate.push_back(PoseFromXYZRPY(i, 0, 0, 0.001 * i, 0, 0));
    }
    KittiSegmentConfig config;
    config.lengths = {100.0};
    const auto errors = ComputeKittiErrors(estimate, reference, config);
    EXPECT_NEAR(errors.translation_percent, 0.0, 1e-9);
    EXPECT_NEAR(errors.rotation_deg_per_100m, 0.001 * 101.0 / 100.0 * 180.0 / kPi * 100.0, 1e-6);
}

}  // namespace
}  // namespace revisit
