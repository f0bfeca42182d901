#include "evaluation/relation_metric.hpp"

#include "core/error.hpp"
#include "core/se3.hpp"

#include <algorithm>
#include <cmath>
#include <istream>
#include <numeric>
#include <optional>
#include <sstream>
#include <string>

namespace revisit {
namespace {

/// Index of the pose stamped nearest to `t`, when within `tolerance`.
std::optional<std::size_t> NearestStamp(const std::vector<double>& stamps, const std::vector<std::size_t>& order,
                                        double t, double tolerance) {
    const auto it = std::lower_bound(order.begin(), order.end(), t,
                                     [&](std::size_t index, double value) { return stamps[index] < value; });
    std::optional<std::size_t> best;
    double best_difference = tolerance;
    for (auto candidate = it == order.begin() ? it : it - 1; candidate != order.end() && candidate <= it; ++candidate) {
        const double difference = std::abs(stamps[*candidate] - t);
        if (difference <= best_difference) {
            best = *candidate;
            best_difference = difference;
        }
    }
    return best;
}

}  // namespace

std::vector<Relation> ParseRelations(std::istream& in, const std::filesystem::path& source) {
    std::vector<Relation> relations;
    std::string line;
    for (std::size_t line_number = 1; std::getline(in, line); ++line_number) {
        const auto start = line.find_first_not_of(" \t\r");
        if (start == std::string::npos || line[start] == '#') continue;
        std::istringstream fields(line);
        double values[8];
        for (double& value : values)
            if (!(fields >> value)) throw DatasetError(source, "expected 8 numbers: t1 t2 x y z roll pitch yaw", line_number);
        std::string extra;
        if (fields >> extra) throw DatasetError(source, "more than 8 fields", line_number);
        for (const double value : values)
            if (!std::isfinite(value)) throw DatasetError(source, "non-finite value", line_number);
        relations.push_back(
            {values[0], values[1], PoseFromXYZRPY(values[2], values[3], values[4], values[5], values[6], values[7])});
    }
    return relations;
}

RelationErrors EvaluateRelations(const Trajectory& trajectory, const std::vector<Relation>& relations,
                                 const RelationMetricConfig& config) {
    if (!trajectory.has_timestamps()) throw ConfigError("relation metric: the trajectory has no timestamps");
    constexpr double kDegPerRad = 180.0 / M_PI;
    std::vector<std::size_t> order(trajectory.size());
    std::iota(order.begin(), order.end(), std::size_t{0});
    std::stable_sort(order.begin(), order.end(),
                     [&](std::size_t a, std::size_t b) { return trajectory.timestamps[a] < trajectory.timestamps[b]; });
    RelationErrors result;
    std::vector<double> translation, translation_squared, rotation, rotation_squared;
    for (const auto& relation : relations) {
        const auto i = NearestStamp(trajectory.timestamps, order, relation.t1, config.max_time_difference);
        const auto j = NearestStamp(trajectory.timestamps, order, relation.t2, config.max_time_difference);
        if (!i || !j) {
            ++result.num_unmatched;
            continue;
        }
        const Eigen::Isometry3d T_1_2_est = trajectory.poses[*i].inverse() * trajectory.poses[*j];
        const Eigen::Isometry3d error = relation.T_1_2.inverse() * T_1_2_est;
        const double t = error.translation().norm();
        const double r = RotationAngle(error) * kDegPerRad;
        translation.push_back(t);
        translation_squared.push_back(t * t);
        rotation.push_back(r);
        rotation_squared.push_back(r * r);
        ++result.num_used;
    }
    result.translation = ComputeStatistics(translation);
    result.translation_squared = ComputeStatistics(translation_squared);
    result.rotation_deg = ComputeStatistics(rotation);
    result.rotation_deg_squared = ComputeStatistics(rotation_squared);
    return result;
}

}  // namespace revisit
