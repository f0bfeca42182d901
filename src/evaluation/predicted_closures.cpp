#include "evaluation/predicted_closures.hpp"

#include "core/error.hpp"

#include <string>

namespace revisit {
namespace {

void CheckRange(std::size_t first, std::size_t last, std::size_t num_scans) {
    if (first > last || last >= num_scans)
        throw ConfigError("map closure scans " + std::to_string(first) + ".." + std::to_string(last) +
                          " outside the " + std::to_string(num_scans) + " odometry poses");
}

}  // namespace

std::vector<ScoredPair> ExpandMapClosures(const std::vector<MapClosureForEval>& closures, const Poses& T_odom_sensor,
                                          const PredictedClosureConfig& config) {
    const double max_squared = config.max_distance * config.max_distance;
    std::vector<Eigen::Vector3d> query_positions;
    // Twice over the closures: first counting, then filling a vector of exactly that size (a walk's
    // closures predict millions of pairs, and a growing vector would hold up to twice their bytes).
    const auto expand = [&](const auto& emit) {
        for (const auto& closure : closures) {
            CheckRange(closure.query_first_scan, closure.query_last_scan, T_odom_sensor.size());
            CheckRange(closure.ref_first_scan, closure.ref_last_scan, T_odom_sensor.size());
            // Positions of the query map's scans in the query map frame.
            const Eigen::Isometry3d T_query_odom = T_odom_sensor[closure.query_first_scan].inverse();
            query_positions.clear();
            for (std::size_t q = closure.query_first_scan; q <= closure.query_last_scan; ++q)
                query_positions.push_back((T_query_odom * T_odom_sensor[q]).translation());
            // Reference map's scans moved into the query map frame by the estimated relative pose.
            const Eigen::Isometry3d T_query_odomref = closure.T_query_ref * T_odom_sensor[closure.ref_first_scan].inverse();
            for (std::size_t r = closure.ref_first_scan; r <= closure.ref_last_scan; ++r) {
                const Eigen::Vector3d ref_position = (T_query_odomref * T_odom_sensor[r]).translation();
                for (std::size_t k = 0; k < query_positions.size(); ++k) {
                    Eigen::Vector3d delta = query_positions[k] - ref_position;
                    if (config.planar) delta.z() = 0.0;
                    if (delta.squaredNorm() < max_squared) emit(closure, r, k);
                }
            }
        }
    };
    std::size_t count = 0;
    expand([&count](const MapClosureForEval&, std::size_t, std::size_t) { ++count; });
    std::vector<ScoredPair> predicted;
    predicted.reserve(count);
    expand([&predicted](const MapClosureForEval& closure, std::size_t r, std::size_t k) {
        predicted.push_back({MakeScanPair(r, closure.query_first_scan + k), closure.inliers});
    });
    return predicted;
}

std::size_t CountPairsWithinTau(const std::vector<ScanPair>& ground_truth, const Poses& T_world_sensor,
                                const PredictedClosureConfig& config) {
    std::size_t within = 0;
    for (const auto& pair : ground_truth) {
        if (pair.second >= T_world_sensor.size())
            throw ConfigError("ground-truth scan pair " + std::to_string(pair.first) + "," + std::to_string(pair.second) +
                              " outside the " + std::to_string(T_world_sensor.size()) + " reference poses");
        Eigen::Vector3d delta = T_world_sensor[pair.second].translation() - T_world_sensor[pair.first].translation();
        if (config.planar) delta.z() = 0.0;
        within += delta.norm() < config.max_distance;
    }
    return within;
}

}  // namespace revisit
