#include "closures/ransac2d.hpp"

#include <Eigen/SVD>
#include <algorithm>

namespace revisit {
namespace {

Eigen::Isometry2d RigidFromTwo(const PointPair& a, const PointPair& b) {
    // Closed form of Kabsch-Umeyama for two points: rotation from the angle between the segments.
    const Eigen::Vector2d dr = b.ref - a.ref, dq = b.query - a.query;
    const double angle = std::atan2(dq.y(), dq.x()) - std::atan2(dr.y(), dr.x());
    Eigen::Isometry2d T = Eigen::Isometry2d::Identity();
    T.linear() = Eigen::Rotation2Dd(angle).toRotationMatrix();
    T.translation() = 0.5 * (a.query + b.query) - T.linear() * (0.5 * (a.ref + b.ref));
    return T;
}

int CountInliers(const std::vector<PointPair>& pairs, const Eigen::Isometry2d& T, double gate2,
                 std::vector<std::uint8_t>* mask) {
    int count = 0;
    const Eigen::Matrix2d R = T.linear();
    const Eigen::Vector2d t = T.translation();
    for (std::size_t i = 0; i < pairs.size(); ++i) {
        const bool inlier = (R * pairs[i].ref + t - pairs[i].query).squaredNorm() < gate2;
        count += inlier;
        if (mask) (*mask)[i] = inlier;
    }
    return count;
}

}  // namespace

Eigen::Isometry2d SolveRigid2D(const std::vector<PointPair>& pairs) {
    Eigen::Isometry2d T = Eigen::Isometry2d::Identity();
    if (pairs.empty()) return T;
    Eigen::Vector2d mean_ref = Eigen::Vector2d::Zero(), mean_query = Eigen::Vector2d::Zero();
    double total = 0.0;
    for (const auto& p : pairs) {
        mean_ref += p.weight * p.ref;
        mean_query += p.weight * p.query;
        total += p.weight;
    }
    if (!(total > 0.0)) return T;
    mean_ref /= total;
    mean_query /= total;
    Eigen::Matrix2d covariance = Eigen::Matrix2d::Zero();
    for (const auto& p : pairs) covariance += p.weight * (p.query - mean_query) * (p.ref - mean_ref).transpose();
    const Eigen::JacobiSVD<Eigen::Matrix2d> svd(covariance, Eigen::ComputeFullU | Eigen::ComputeFullV);
    Eigen::Matrix2d S = Eigen::Matrix2d::Identity();
    if ((svd.matrixU() * svd.matrixV().transpose()).determinant() < 0) S(1, 1) = -1.0;
    T.linear() = svd.matrixU() * S * svd.matrixV().transpose();
    T.translation() = mean_query - T.linear() * mean_ref;
    return T;
}

RansacResult AlignRansac2D(const std::vector<PointPair>& pairs, const RansacConfig& config, std::mt19937& rng) {
    RansacResult result;
    const int n = int(pairs.size());
    result.inliers.assign(pairs.size(), 0);
    if (n < 2) return result;
    const double gate2 = config.inlier_distance * config.inlier_distance;
    const int max_trials = config.max_trials > 0 ? config.max_trials : n * (n - 1);

    std::vector<double> weights(pairs.size());
    for (int i = 0; i < n; ++i) weights[i] = config.weighted_sampling ? std::max(pairs[i].weight, 1e-9) : 1.0;
    std::discrete_distribution<int> pick(weights.begin(), weights.end());  // one generator, never re-seeded

    Eigen::Isometry2d best = Eigen::Isometry2d::Identity();
    int best_count = -1;
    for (int trial = 0; trial < max_trials; ++trial) {
        const int a = pick(rng);
        const int b = pick(rng);
        ++result.trials;
        if (a == b || (pairs[a].ref - pairs[b].ref).squaredNorm() < 1e-12) continue;
        const Eigen::Isometry2d T = RigidFromTwo(pairs[a], pairs[b]);
        const int count = CountInliers(pairs, T, gate2, nullptr);
        if (count > best_count) {
            best_count = count;
            best = T;
            if (count >= config.early_stop_inliers) break;
        }
    }
    if (best_count < 0) return result;
    result.num_inliers = CountInliers(pairs, best, gate2, &result.inliers);
    if (config.refit_inliers && result.num_inliers >= 2) {
        // Refit on the inliers, iteratively reweighted (Cauchy weights with scale gate / 3) so that the
        // loosely gated matches near the 3-pixel border pull less than the tight ones.
        const double scale2 = gate2 / 9.0;
        Eigen::Isometry2d refit = best;
        for (int iteration = 0; iteration < 10; ++iteration) {
            std::vector<PointPair> weighted;
            for (int i = 0; i < n; ++i) {
                const double r2 = (refit * pairs[i].ref - pairs[i].query).squaredNorm();
                if (r2 < gate2) weighted.push_back({pairs[i].ref, pairs[i].query, 1.0 / (1.0 + r2 / scale2)});
            }
            if (weighted.size() < 2) break;
            refit = SolveRigid2D(weighted);
        }
        std::vector<std::uint8_t> refit_mask(pairs.size(), 0);
        const int refit_count = CountInliers(pairs, refit, gate2, &refit_mask);
        if (refit_count >= 2) {
            best = refit;
            result.num_inliers = refit_count;
            result.inliers = std::move(refit_mask);
        }
    }
    result.T_query_ref = best;
    return result;
}

}  // namespace revisit
