#pragma once
/// 2D rigid alignment of matched keypoints with RANSAC (METHOD.md section 5; thesis section 4.4).
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <random>
#include <vector>

namespace revisit {

/// One correspondence: a reference point and the query point it should map onto [m].
struct PointPair {
    Eigen::Vector2d ref;
    Eigen::Vector2d query;
    double weight = 1.0;  ///< sampling weight (paper-era code: from the descriptor distance)
};

/// How hypotheses are drawn.
enum class RansacSampling {
    /// Every distinct pair once, pairs of the best descriptor matches first (when weighted_sampling):
    /// covers every hypothesis the paper-era n(n-1) random draws can reach, deterministically.
    kExhaustive,
    kRandom,  ///< paper-era and later code: random draws from the seeded generator
};

struct RansacConfig {
    double inlier_distance = 1.5;  ///< [m] 3 pixels at nu_res = 0.5 m
    RansacSampling sampling = RansacSampling::kExhaustive;
    /// Cap on hypotheses. 0: all n(n-1)/2 pairs (exhaustive) or n(n-1) draws (random, as the paper-era
    /// code); later code: 688 random draws.
    int max_trials = 0;
    int early_stop_inliers = 30;   ///< stop as soon as a hypothesis has this many inliers
    /// Paper-era code: prefer matches of small descriptor distance (random: draw them more often;
    /// exhaustive: try their pairs first).
    bool weighted_sampling = true;
    /// Final Kabsch-Umeyama on the inliers of the best hypothesis (later code). On by default although the
    /// paper does not describe it: without it the best 2-point hypothesis is off by ~0.8 m on KITTI.
    bool refit_inliers = true;
    std::uint32_t seed = 42;       ///< kRandom: the detector seeds one generator per candidate from this
};

struct RansacResult {
    Eigen::Isometry2d T_query_ref = Eigen::Isometry2d::Identity();
    std::vector<std::uint8_t> inliers;  ///< one flag per pair
    int num_inliers = 0;
    int trials = 0;      ///< hypotheses drawn
    int hypotheses = 0;  ///< of which scored: a sample whose two matches cannot both fit a rigid motion is skipped
};

/// 2D rigid transform mapping `ref` onto `query` in the weighted least-squares sense (Kabsch-Umeyama, no scale,
/// reflection removed by the sign of the determinant); thesis Eq. (3.10)-(3.11).
Eigen::Isometry2d SolveRigid2D(const std::vector<PointPair>& pairs);

/// RANSAC over 2-point samples; the 2 points of a sample must be distinct. `rng` is used by kRandom only.
RansacResult AlignRansac2D(const std::vector<PointPair>& pairs, const RansacConfig& config, std::mt19937& rng);

}  // namespace revisit
