#include <gtest/gtest.h>

#include "closures/ransac2d.hpp"

namespace revisit {
namespace {

Eigen::Isometry2d Rigid2D(double x, double y, double yaw_deg) {
    Eigen::Isometry2d T = Eigen::Isometry2d::Identity();
    T.linear() = Eigen::Rotation2Dd(yaw_deg * M_PI / 180.0).toRotationMatrix();
    T.translation() = Eigen::Vector2d(x, y);
    return T;
}

std::vector<PointPair> MakePairs(const Eigen::Isometry2d& T, int inliers, int outliers, std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> coord(-80.0, 80.0);
    std::vector<PointPair> pairs;
    for (int i = 0; i < inliers + outliers; ++i) {
        const Eigen::Vector2d ref(coord(rng), coord(rng));
        pairs.push_back({ref, i < inliers ? Eigen::Vector2d(T * ref) : Eigen::Vector2d(coord(rng), coord(rng)), 1.0});
    }
    std::shuffle(pairs.begin(), pairs.end(), rng);
    return pairs;
}

TEST(SolveRigid2D, ExactOnNoiseFreePointsAndNeverAReflection) {
    const auto T = Rigid2D(12.0, -3.5, 137.0);
    const auto pairs = MakePairs(T, 20, 0, 1);
    const auto estimate = SolveRigid2D(pairs);
    EXPECT_NEAR((estimate.matrix() - T.matrix()).norm(), 0.0, 1e-9);
    // Mirrored points: the best proper rotation, determinant +1.
    auto mirrored = pairs;
    for (auto& p : mirrored) p.query.x() = -p.query.x();
    EXPECT_NEAR(SolveRigid2D(mirrored).linear().determinant(), 1.0, 1e-9);
}

TEST(AlignRansac2D, RecoversKnownTransformDespiteOutliers) {
    const auto T_true = Rigid2D(12.0, -3.5, 37.0);
    const auto pairs = MakePairs(T_true, 25, 60, 7);
    for (const auto& [sampling, refit] : {std::pair{RansacSampling::kExhaustive, false}, std::pair{RansacSampling::kExhaustive, true},
                                        std::pair{RansacSampling::kRandom, false}, std::pair{RansacSampling::kRandom, true}}) {
        RansacConfig config;
        config.sampling = sampling;
        config.refit_inliers = refit;
        config.early_stop_inliers = 1000;  // examine all pairs
        std::mt19937 rng(1);
        const auto result = AlignRansac2D(pairs, config, rng);
        EXPECT_EQ(result.num_inliers, 25);
        EXPECT_NEAR((result.T_query_ref.translation() - T_true.translation()).norm(), 0.0, 1e-6);
        for (std::size_t i = 0; i < pairs.size(); ++i) {
            const bool truly = (T_true * pairs[i].ref - pairs[i].query).norm() < 1e-9;
            EXPECT_EQ(bool(result.inliers[i]), truly);
        }
    }
}

TEST(AlignRansac2D, SameSeedSameResultAndEarlyStopCutsTrials) {
    const auto pairs = MakePairs(Rigid2D(-5.0, 9.0, -120.0), 60, 40, 3);
    RansacConfig config;
    config.sampling = RansacSampling::kRandom;
    config.max_trials = 688;
    std::mt19937 rng_a(5), rng_b(5);
    const auto a = AlignRansac2D(pairs, config, rng_a), b = AlignRansac2D(pairs, config, rng_b);
    EXPECT_EQ(a.trials, b.trials);
    EXPECT_EQ(a.inliers, b.inliers);
    EXPECT_LT(a.trials, 100);  // 60% inliers: a 30-inlier hypothesis appears within a few trials
    EXPECT_GE(a.num_inliers, 30);
}

TEST(AlignRansac2D, ExhaustiveTriesEveryPairOnceAndScoresOnlyConsistentSamples) {
    // 12 true matches among 200 (6%): random draws need many trials to hit two of them.
    const auto T_true = Rigid2D(3.0, 30.0, 75.0);
    const auto pairs = MakePairs(T_true, 12, 188, 21);
    RansacConfig config;
    config.early_stop_inliers = 1000;
    std::mt19937 rng(1);
    const auto result = AlignRansac2D(pairs, config, rng);
    EXPECT_EQ(result.trials, 200 * 199 / 2);
    EXPECT_EQ(result.num_inliers, 12);
    EXPECT_NEAR((result.T_query_ref.translation() - T_true.translation()).norm(), 0.0, 1e-3);
    // Outlier pairs rarely preserve their length within two gates: most samples are never scored.
    EXPECT_GE(result.hypotheses, 12 * 11 / 2);
    EXPECT_LT(result.hypotheses, result.trials / 5);
    // Deterministic without a generator: a differently seeded one changes nothing.
    std::mt19937 other(99);
    const auto again = AlignRansac2D(pairs, config, other);
    EXPECT_EQ(again.inliers, result.inliers);
    EXPECT_EQ(again.T_query_ref.matrix(), result.T_query_ref.matrix());
    // The cap on hypotheses holds.
    config.max_trials = 500;
    EXPECT_EQ(AlignRansac2D(pairs, config, rng).trials, 500);
}

TEST(AlignRansac2D, WeightedExhaustiveTriesTheBestMatchesFirst) {
    // The true matches carry the highest weights (smallest descriptor distances): their pairs come first,
    // and the early stop ends the search after at most the pairs among them and a few more.
    const auto T_true = Rigid2D(-20.0, 4.0, -30.0);
    auto pairs = MakePairs(T_true, 40, 160, 5);
    for (auto& p : pairs) p.weight = (T_true * p.ref - p.query).norm() < 1e-9 ? 40.0 : 10.0;
    RansacConfig config;
    std::mt19937 rng(1);
    const auto result = AlignRansac2D(pairs, config, rng);
    EXPECT_LE(result.trials, 40 * 39 / 2);
    EXPECT_GE(result.num_inliers, 40);
}

TEST(AlignRansac2D, NoisyInliersRefitImprovesAccuracy) {
    const auto T_true = Rigid2D(40.0, 20.0, 10.0);
    auto pairs = MakePairs(T_true, 80, 40, 9);
    std::mt19937 noise_rng(2);
    std::normal_distribution<double> noise(0.0, 0.25);
    for (auto& p : pairs) p.query += Eigen::Vector2d(noise(noise_rng), noise(noise_rng));
    RansacConfig config;
    config.refit_inliers = true;
    config.max_trials = 688;
    std::mt19937 rng(1);
    const auto result = AlignRansac2D(pairs, config, rng);
    EXPECT_LT((result.T_query_ref.translation() - T_true.translation()).norm(), 0.2);
    EXPECT_LT(std::abs(Eigen::Rotation2Dd(result.T_query_ref.linear()).angle() - 10.0 * M_PI / 180.0), 0.5 * M_PI / 180.0);
}

}  // namespace
}  // namespace revisit
