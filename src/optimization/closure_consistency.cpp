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

}  // namespace

double CycleChi2(const ConsistencyClosure& a, const ConsistencyClosure& b, const ConsistencyOdometry& odometry,
                 const OdometryNoise& noise, const ClosureConsistencyConfig& config) {
    const Eigen::Isometry3d cycle = a.T_query_ref * Odometry(odometry, a.ref_node, b.ref_node) * b.T_query_ref.inverse() *
                                    Odometry(odometry, b.query_node, a.query_node);
    double var_t = 2.0 * config.closure_sigma_translation * config.closure_sigma_translation;
    const double sigma_closure_rotation = config.closure_sigma_rotation_deg * M_PI / 180.0;
    double var_r = 2.0 * sigma_closure_rotation * sigma_closure_rotation;
    const std::pair<int, int> legs[] = {{a.ref_node, b.ref_node}, {b.query_node, a.query_node}};
    for (const auto& [from, to] : legs) {
        const double travel = Travel(odometry, from, to);
        const double sigma_t = std::max(noise.min_translation, noise.translation_per_m * travel);
        const double sigma_r = std::max(noise.min_rotation, noise.rotation_per_m * travel);
        // Heading drift along the leg also moves its end: sigma_r times the mean distance from the path
        // to its end, travel / 2 on a straight leg (rotation_per_m * travel^2 / 2). Where heading drifts
        // faster than position (2D lasers indoors) this dominates the cycle's translation error.
        const double swing = sigma_r * travel / 2.0;
        var_t += sigma_t * sigma_t + swing * swing;
        var_r += sigma_r * sigma_r;
    }
    const double angle = Eigen::AngleAxisd(cycle.linear()).angle();
    return cycle.translation().squaredNorm() / var_t + angle * angle / var_r;
}

std::vector<std::size_t> MaximumClique(const std::vector<std::vector<char>>& adjacency, const std::vector<double>& weight,
                                       int max_steps) {
    return CliqueSearch(adjacency, weight, max_steps).Run();
}

void ClosureConsistency::Add(const ConsistencyClosure& closure, const ConsistencyOdometry& odometry) {
    const std::size_t v = closures_.size();
    std::vector<char> row(v + 1, 1);
    for (std::size_t k = 0; k < v; ++k) {
        row[k] = CycleChi2(closures_[k], closure, odometry, noise_, config_) <= config_.chi2_threshold;
        consistent_[k].push_back(row[k]);
    }
    closures_.push_back(closure);
    consistent_.push_back(row);
    in_set_.push_back(0);

    // Incremental maximum clique: a new vertex grows the largest clique by at most one, and only with
    // its own neighbours. If it agrees with the whole current set, the set plus it is maximum;
    // otherwise the only possible better set is it plus a clique among its neighbours.
    bool agrees_with_set = true;
    for (std::size_t k = 0; k < v && agrees_with_set; ++k) agrees_with_set = !in_set_[k] || row[k];
    if (agrees_with_set) {
        in_set_[v] = 1;
        ++set_size_;
        set_weight_ += closure.score;
        return;
    }
    std::vector<std::size_t> neighbours;
    for (std::size_t k = 0; k < v; ++k)
        if (row[k]) neighbours.push_back(k);
    if (neighbours.size() + 1 < set_size_) return;
    std::vector<std::vector<char>> adjacency(neighbours.size(), std::vector<char>(neighbours.size(), 0));
    std::vector<double> weight(neighbours.size());
    for (std::size_t a = 0; a < neighbours.size(); ++a) {
        weight[a] = closures_[neighbours[a]].score;
        for (std::size_t b = 0; b < neighbours.size(); ++b) adjacency[a][b] = consistent_[neighbours[a]][neighbours[b]];
    }
    const auto clique = MaximumClique(adjacency, weight, config_.exact_max_steps);
    double clique_weight = closure.score;
    for (std::size_t a : clique) clique_weight += weight[a];
    if (clique.size() + 1 < set_size_ || (clique.size() + 1 == set_size_ && clique_weight <= set_weight_)) return;
    std::fill(in_set_.begin(), in_set_.end(), 0);
    for (std::size_t a : clique) in_set_[neighbours[a]] = 1;
    in_set_[v] = 1;
    set_size_ = clique.size() + 1;
    set_weight_ = clique_weight;
}

std::vector<char> ClosureConsistency::ConsistentSet() const {
    return config_.enabled ? in_set_ : std::vector<char>(closures_.size(), 1);
}

}  // namespace revisit
