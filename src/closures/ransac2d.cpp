#include "closures/ransac2d.hpp"

#include <Eigen/SVD>
#include <algorithm>
#include <cmath>

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

/// The order in which exhaustive sampling pairs the matches: heaviest first when weighted.
std::vector<int> MatchOrder(const std::vector<PointPair>& pairs, bool weighted) {
    std::vector<int> order(pairs.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = int(i);
    if (weighted) {
        std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return pairs[a].weight > pairs[b].weight; });
    }
    return order;
}

/// The pairs as float columns, in a given order: scoring a hypothesis and checking samples are the hot
/// loops, and this layout vectorizes.
struct PairColumns {
    std::vector<float> rx, ry, qx, qy;
    PairColumns(const std::vector<PointPair>& pairs, const std::vector<int>& order) {
        for (const int i : order) {
            rx.push_back(float(pairs[i].ref.x()));
            ry.push_back(float(pairs[i].ref.y()));
            qx.push_back(float(pairs[i].query.x()));
            qy.push_back(float(pairs[i].query.y()));
        }
    }
};

/// Inliers of T, flagged in `mask` when given. The count alone is the hot loop: kept branch-free so that
/// it vectorizes.
int CountInliers(const PairColumns& c, const Eigen::Isometry2d& T, double gate2, std::vector<std::uint8_t>* mask = nullptr) {
    const float r00 = float(T.linear()(0, 0)), r01 = float(T.linear()(0, 1)), r10 = float(T.linear()(1, 0)),
                r11 = float(T.linear()(1, 1)), tx = float(T.translation().x()), ty = float(T.translation().y());
    const float g2 = float(gate2);
    const auto inlier = [&](std::size_t i) {
        const float dx = r00 * c.rx[i] + r01 * c.ry[i] + tx - c.qx[i];
        const float dy = r10 * c.rx[i] + r11 * c.ry[i] + ty - c.qy[i];
        return dx * dx + dy * dy < g2;
    };
    const std::size_t n = c.rx.size();
    int count = 0;
    if (mask) {
        for (std::size_t i = 0; i < n; ++i) count += ((*mask)[i] = inlier(i));
    } else {
        for (std::size_t i = 0; i < n; ++i) count += inlier(i) ? 1 : 0;
    }
    return count;
}

/// Sample consistency of matches i and j: RigidFromTwo aligns the midpoints, so each of the two is off by
/// half the difference of the segment lengths a (reference) and b (query). Unless |a - b| < 2 gate, the
/// hypothesis is not supported even by its own sample, and scoring it would be wasted (most samples of a
/// wrong candidate fail here). Evaluated without roots, as a^2 + b^2 - 4 gate^2 < 0 or its square < 4 a^2 b^2,
/// so that loops over j vectorize. Samples of one reference point (a = 0) are degenerate.
inline bool Consistent(const PairColumns& c, int i, int j, float four_gate2) {
    const float drx = c.rx[j] - c.rx[i], dry = c.ry[j] - c.ry[i], dqx = c.qx[j] - c.qx[i], dqy = c.qy[j] - c.qy[i];
    const float a2 = drx * drx + dry * dry, b2 = dqx * dqx + dqy * dqy, s = a2 + b2 - four_gate2;
    return a2 > 0.f && (s < 0.f || s * s < 4.f * a2 * b2);
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
    const float four_gate2 = float(4.0 * gate2);
    const PairColumns columns(pairs, MatchOrder(pairs, false));

    Eigen::Isometry2d best = Eigen::Isometry2d::Identity();
    int best_count = -1;
    // Scores the hypothesis of (consistent) matches a and b; true when the early stop is reached.
    const auto score = [&](int a, int b) {
        ++result.hypotheses;
        const Eigen::Isometry2d T = RigidFromTwo(pairs[a], pairs[b]);
        const int count = CountInliers(columns, T, gate2);
        if (count <= best_count) return false;
        best_count = count;
        best = T;
        return count >= config.early_stop_inliers;
    };

    if (config.sampling == RansacSampling::kExhaustive) {
        // Progressive order: after step i, every pair among the i + 1 best matches has been tried.
        const auto order = MatchOrder(pairs, config.weighted_sampling);
        const PairColumns ordered(pairs, order);
        std::vector<std::uint8_t> consistent(pairs.size());
        long long remaining = config.max_trials > 0 ? config.max_trials : (long long)n * (n - 1) / 2;
        bool done = false;
        for (int i = 1; i < n && remaining > 0 && !done; ++i) {
            const int count = int(std::min<long long>(i, remaining));
            for (int j = 0; j < count; ++j) consistent[j] = Consistent(ordered, i, j, four_gate2);
            int tried = count;
            for (int j = 0; j < count && !done; ++j) {
                if (consistent[j] && score(order[i], order[j])) done = true, tried = j + 1;
            }
            result.trials += tried;
            remaining -= tried;
        }
    } else {
        const int max_trials = config.max_trials > 0 ? config.max_trials : n * (n - 1);
        std::vector<double> weights(pairs.size());
        for (int i = 0; i < n; ++i) weights[i] = config.weighted_sampling ? std::max(pairs[i].weight, 1e-9) : 1.0;
        std::discrete_distribution<int> pick(weights.begin(), weights.end());  // one generator, never re-seeded
        for (int trial = 0; trial < max_trials; ++trial) {
            const int a = pick(rng);
            const int b = pick(rng);
            ++result.trials;
            if (a != b && Consistent(columns, a, b, four_gate2) && score(a, b)) break;
        }
    }
    if (best_count < 0) return result;
    result.num_inliers = CountInliers(columns, best, gate2, &result.inliers);
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
        const int refit_count = CountInliers(columns, refit, gate2, &refit_mask);
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
