#include "optimization/closure_consistency.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>

namespace revisit {
namespace {

/// Branch and bound over cliques (Carraghan-Pardalos order), candidate sets as bitsets over the
/// vertices renumbered most-connected first, so that one step costs n / 64 word operations.
class CliqueSearch {
  public:
    using Bits = std::vector<std::uint64_t>;

    CliqueSearch(const std::vector<std::vector<char>>& adjacency, const std::vector<double>& weight, int max_steps)
        : n_(adjacency.size()), words_((n_ + 63) / 64), steps_left_(max_steps) {
        std::vector<int> degree(n_, 0);
        for (std::size_t i = 0; i < n_; ++i)
            for (std::size_t j = 0; j < n_; ++j) degree[i] += i != j && adjacency[i][j];
        order_.resize(n_);
        std::iota(order_.begin(), order_.end(), std::size_t(0));
        // Most connected first: the greedy start is then usually the answer and prunes hard.
        std::stable_sort(order_.begin(), order_.end(), [&](std::size_t a, std::size_t b) {
            return degree[a] != degree[b] ? degree[a] > degree[b] : weight[a] > weight[b];
        });
        weight_.resize(n_);
        adjacency_.assign(n_, Bits(words_, 0));
        for (std::size_t a = 0; a < n_; ++a) {
            weight_[a] = weight[order_[a]];
            for (std::size_t b = 0; b < n_; ++b)
                if (a != b && adjacency[order_[a]][order_[b]]) Set(adjacency_[a], b);
        }
    }

    std::vector<std::size_t> Run() {
        for (std::size_t v = 0; v < n_; ++v) {
            bool fits = true;
            for (std::size_t u : best_) fits = fits && Test(adjacency_[u], v);
            if (fits) best_.push_back(v), best_weight_ += weight_[v];
        }
        Bits all(words_, 0);
        for (std::size_t v = 0; v < n_; ++v) Set(all, v);
        std::vector<std::size_t> current;
        Expand(current, 0.0, all);
        std::vector<std::size_t> result;
        for (std::size_t v : best_) result.push_back(order_[v]);
        std::sort(result.begin(), result.end());
        return result;
    }

  private:
    static void Set(Bits& bits, std::size_t i) { bits[i / 64] |= std::uint64_t(1) << (i % 64); }
    static bool Test(const Bits& bits, std::size_t i) { return (bits[i / 64] >> (i % 64)) & 1u; }
    static std::size_t Count(const Bits& bits) {
        std::size_t count = 0;
        for (std::uint64_t w : bits) count += std::size_t(__builtin_popcountll(w));
        return count;
    }
    double Weight(const Bits& bits) const {
        double sum = 0.0;
        for (std::size_t v = 0; v < n_; ++v) sum += Test(bits, v) ? weight_[v] : 0.0;
        return sum;
    }

    void Expand(std::vector<std::size_t>& current, double current_weight, Bits candidates) {
        if (current.size() > best_.size() || (current.size() == best_.size() && current_weight > best_weight_)) {
            best_ = current;
            best_weight_ = current_weight;
        }
        for (std::size_t word = 0; word < words_; ++word) {
            while (candidates[word] != 0) {
                if (steps_left_-- <= 0) return;
                const std::size_t bound = current.size() + Count(candidates);
                if (bound < best_.size()) return;
                if (bound == best_.size() && current_weight + Weight(candidates) <= best_weight_) return;
                const std::size_t v = word * 64 + std::size_t(__builtin_ctzll(candidates[word]));
                candidates[word] &= candidates[word] - 1;
                Bits next(words_);
                for (std::size_t w = 0; w < words_; ++w) next[w] = candidates[w] & adjacency_[v][w];
                current.push_back(v);
                Expand(current, current_weight + weight_[v], std::move(next));
                current.pop_back();
            }
        }
    }

    std::size_t n_, words_;
    long steps_left_;
    std::vector<std::size_t> order_;  ///< search index -> input index
    std::vector<double> weight_;
    std::vector<Bits> adjacency_;
    std::vector<std::size_t> best_;
    double best_weight_ = 0.0;
};

Eigen::Isometry3d Odometry(const ConsistencyOdometry& odometry, int from, int to) {
    return (*odometry.T_world_node)[std::size_t(from)].inverse() * (*odometry.T_world_node)[std::size_t(to)];
}

double Travel(const ConsistencyOdometry& odometry, int from, int to) {
    return std::abs((*odometry.travel)[std::size_t(to)] - (*odometry.travel)[std::size_t(from)]);
}

using Matrix63d = Eigen::Matrix<double, 6, 3>;

Eigen::Matrix3d Skew(const Eigen::Vector3d& v) {
    Eigen::Matrix3d m;
    m << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
    return m;
}

/// Adjoint of T for right perturbations [translation; rotation]: T Exp(xi) = Exp(Ad xi) T.
Matrix6d Adjoint(const Eigen::Isometry3d& T) {
    Matrix6d ad = Matrix6d::Zero();
    ad.topLeftCorner<3, 3>() = T.linear();
    ad.topRightCorner<3, 3>() = Skew(T.translation()) * T.linear();
    ad.bottomRightCorner<3, 3>() = T.linear();
    return ad;
}

/// The leg's end error per radian of rotation drift about each axis of its end frame, as a right
/// perturbation of the leg [translation; rotation]: a drift accumulated evenly along the path turns
/// the end about the path's mean position, so the end moves by angle x (end - mean).
Matrix63d DriftColumns(const ConsistencyOdometry& odometry, int from, int to) {
    const Eigen::Isometry3d& T_world_to = (*odometry.T_world_node)[std::size_t(to)];
    const Eigen::Vector3d& p_from = (*odometry.T_world_node)[std::size_t(from)].translation();
    Eigen::Vector3d mean = 0.5 * (p_from + T_world_to.translation());
    const double travel = (*odometry.travel)[std::size_t(to)] - (*odometry.travel)[std::size_t(from)];
    if (odometry.position_integral != nullptr && std::abs(travel) > 1e-9)
        mean = ((*odometry.position_integral)[std::size_t(to)] - (*odometry.position_integral)[std::size_t(from)]) / travel;
    // Rotating the end by w about the mean moves it by w x (end - mean): in the end frame, -[d]x w.
    const Eigen::Vector3d d = T_world_to.linear().transpose() * (T_world_to.translation() - mean);
    Matrix63d columns;
    columns.topRows<3>() = -Skew(d);
    columns.bottomRows<3>() = Eigen::Matrix3d::Identity();
    return columns;
}

/// [m^2] Variance of the leg end's position that its rotation drift leaves unexplained by the drift
/// angle at its end: a drift that wanders (a random walk, not an even rate) moves the end by
/// sigma_r x travel / sqrt(12) beyond what the end's angle shows (the conditional of the random walk).
double WanderVariance(double sigma_r, double travel) {
    const double sigma = sigma_r * travel / std::sqrt(12.0);
    return sigma * sigma;
}

/// [translation; rotation vector] of a pose near identity (the cycle's residual).
Eigen::Matrix<double, 6, 1> Residual(const Eigen::Isometry3d& cycle) {
    const Eigen::AngleAxisd rotation(cycle.linear());
    Eigen::Matrix<double, 6, 1> e;
    e << cycle.translation(), rotation.angle() * rotation.axis();
    return e;
}

}  // namespace

void AppendPositionIntegral(const Poses& T_world_node, const std::vector<double>& travel, std::vector<Eigen::Vector3d>& integral) {
    for (std::size_t i = integral.size(); i < T_world_node.size(); ++i) {
        if (i == 0) {
            integral.push_back(Eigen::Vector3d::Zero());
            continue;
        }
        const Eigen::Vector3d mid = 0.5 * (T_world_node[i - 1].translation() + T_world_node[i].translation());
        integral.push_back(integral[i - 1] + mid * (travel[i] - travel[i - 1]));
    }
}

double CycleChi2(const ConsistencyClosure& a, const ConsistencyClosure& b, const ConsistencyOdometry& odometry,
                 const OdometryNoise& noise, const ClosureConsistencyConfig& config) {
    // cycle = A * leg_ref * C with A = T_qa_ra, leg_ref = odom(ra -> rb), C = T_qb_rb^-1 * leg_query and
    // leg_query = odom(qb -> qa). A right perturbation xi of leg_ref moves the cycle by Ad(C^-1) xi,
    // one of leg_query by xi itself (it is the last factor).
    const Eigen::Isometry3d leg_query = Odometry(odometry, b.query_node, a.query_node);
    const Eigen::Isometry3d C = b.T_query_ref.inverse() * leg_query;
    const Eigen::Isometry3d cycle = a.T_query_ref * Odometry(odometry, a.ref_node, b.ref_node) * C;

    const double sigma_closure_rotation = config.closure_sigma_rotation_deg * M_PI / 180.0;
    double var_t = 2.0 * config.closure_sigma_translation * config.closure_sigma_translation;
    Matrix6d covariance = Matrix6d::Zero();
    covariance.bottomRightCorner<3, 3>().diagonal().setConstant(2.0 * sigma_closure_rotation * sigma_closure_rotation);
    const struct {
        int from, to;
        Matrix6d into_cycle;
    } legs[] = {{a.ref_node, b.ref_node, Adjoint(C.inverse())}, {b.query_node, a.query_node, Matrix6d::Identity()}};
    for (const auto& leg : legs) {
        const double travel = Travel(odometry, leg.from, leg.to);
        const double sigma_t = std::max(noise.min_translation, noise.translation_per_m * travel);
        const double sigma_r = std::max(noise.min_rotation, noise.rotation_per_m * travel);
        var_t += sigma_t * sigma_t + WanderVariance(sigma_r, travel);  // isotropic: the same in any frame
        const Matrix63d drift = leg.into_cycle * DriftColumns(odometry, leg.from, leg.to);
        covariance += sigma_r * sigma_r * drift * drift.transpose();
    }
    covariance.topLeftCorner<3, 3>().diagonal().array() += var_t;
    const Eigen::Matrix<double, 6, 1> e = Residual(cycle);
    return e.dot(covariance.ldlt().solve(e));
}

double OdometryChi2(const ConsistencyClosure& closure, const ConsistencyOdometry& odometry, const OdometryNoise& noise,
                    const ClosureConsistencyConfig& config) {
    // The cycle through one closure and one leg: T_query_ref * odom(ref -> query); one closure's sigma.
    const Eigen::Isometry3d cycle = closure.T_query_ref * Odometry(odometry, closure.ref_node, closure.query_node);
    const double sigma_closure_rotation = config.closure_sigma_rotation_deg * M_PI / 180.0;
    const double travel = Travel(odometry, closure.ref_node, closure.query_node);
    const double sigma_t = std::max(noise.min_translation, noise.translation_per_m * travel);
    const double sigma_r = std::max(noise.min_rotation, noise.rotation_per_m * travel);
    const Matrix63d drift = DriftColumns(odometry, closure.ref_node, closure.query_node);
    Matrix6d covariance = sigma_r * sigma_r * drift * drift.transpose();
    covariance.topLeftCorner<3, 3>().diagonal().array() +=
        config.closure_sigma_translation * config.closure_sigma_translation + sigma_t * sigma_t + WanderVariance(sigma_r, travel);
    covariance.bottomRightCorner<3, 3>().diagonal().array() += sigma_closure_rotation * sigma_closure_rotation;
    const Eigen::Matrix<double, 6, 1> e = Residual(cycle);
    return e.dot(covariance.ldlt().solve(e));
}

std::vector<std::size_t> MaximumClique(const std::vector<std::vector<char>>& adjacency, const std::vector<double>& weight,
                                       int max_steps) {
    return CliqueSearch(adjacency, weight, max_steps).Run();
}

void ClosureConsistency::Add(const ConsistencyClosure& closure, const ConsistencyOdometry& odometry, bool may_displace) {
    const std::size_t v = closures_.size();
    may_displace_.push_back(may_displace);
    odometry_chi2_.push_back(odometry.one_chain ? OdometryChi2(closure, odometry, noise_, config_) : 0.0);
    const bool fits_odometry = odometry_chi2_.back() <= config_.odometry_chi2_threshold;
    std::vector<char> row(v + 1, 1);
    for (std::size_t k = 0; k < v; ++k) {
        row[k] = fits_odometry && odometry_chi2_[k] <= config_.odometry_chi2_threshold &&
                 CycleChi2(closures_[k], closure, odometry, noise_, config_) <= config_.chi2_threshold;
        consistent_[k].push_back(row[k]);
    }
    closures_.push_back(closure);
    consistent_.push_back(row);
    in_set_.push_back(0);
    if (!fits_odometry) return;  // agrees with nothing: never in the set

    // Incremental maximum clique: a new vertex grows the largest clique by at most one, and only with
    // its own neighbours. If it agrees with the whole current set, the set plus it is maximum;
    // otherwise the only possible better set is it plus a clique among its neighbours.
    bool agrees_with_set = true;
    for (std::size_t k = 0; k < v && agrees_with_set; ++k) agrees_with_set = !in_set_[k] || row[k];
    if (agrees_with_set) {
        in_set_[v] = 1;
        ++set_size_;
        set_weight_ += TieWeight(v);
        return;
    }
    if (!may_displace) return;
    std::vector<std::size_t> neighbours;
    for (std::size_t k = 0; k < v; ++k)
        if (row[k]) neighbours.push_back(k);
    if (neighbours.size() + 1 < set_size_) return;
    std::vector<std::vector<char>> adjacency(neighbours.size(), std::vector<char>(neighbours.size(), 0));
    std::vector<double> weight(neighbours.size());
    for (std::size_t a = 0; a < neighbours.size(); ++a) {
        weight[a] = TieWeight(neighbours[a]);
        for (std::size_t b = 0; b < neighbours.size(); ++b) adjacency[a][b] = consistent_[neighbours[a]][neighbours[b]];
    }
    const auto clique = MaximumClique(adjacency, weight, config_.exact_max_steps);
    double clique_weight = TieWeight(v);
    for (std::size_t a : clique) clique_weight += weight[a];
    if (clique.size() + 1 < set_size_ || (clique.size() + 1 == set_size_ && clique_weight <= set_weight_)) return;
    std::fill(in_set_.begin(), in_set_.end(), 0);
    for (std::size_t a : clique) in_set_[neighbours[a]] = 1;
    in_set_[v] = 1;
    set_size_ = clique.size() + 1;
    set_weight_ = clique_weight;
}

double ClosureConsistency::TieWeight(std::size_t k) const {
    // The score decides between sets of equal size; between equal scores (a few inliers each) the set
    // that agrees better with the odometry: the fraction stays below one inlier.
    return closures_[k].score + 1.0 / (1.0 + odometry_chi2_[k]);
}

std::optional<double> ClosureConsistency::ObservedRotationRate(const ConsistencyOdometry& odometry,
                                                               std::size_t min_closures) const {
    std::vector<double> rates;  // per closure of the set: [rad/m]
    for (std::size_t k = 0; k < closures_.size(); ++k) {
        const auto& c = closures_[k];
        const double travel = Travel(odometry, c.ref_node, c.query_node);
        if (!in_set_[k] || travel <= 0.0) continue;
        const Eigen::AngleAxisd cycle((c.T_query_ref * Odometry(odometry, c.ref_node, c.query_node)).linear());
        rates.push_back(std::abs(cycle.angle()) / travel);
    }
    if (rates.empty() || rates.size() < min_closures) return std::nullopt;
    return *std::max_element(rates.begin(), rates.end());
}

ClosureConsistency ClosureConsistency::Rechecked(const OdometryNoise& noise, const ConsistencyOdometry& odometry) const {
    ClosureConsistency rechecked(config_, noise);
    for (std::size_t k = 0; k < closures_.size(); ++k) rechecked.Add(closures_[k], odometry, may_displace_[k] != 0);
    return rechecked;
}

std::vector<char> ClosureConsistency::ConsistentSet() const {
    return config_.enabled ? in_set_ : std::vector<char>(closures_.size(), 1);
}

}  // namespace revisit
