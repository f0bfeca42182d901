#pragma once
/// The relation-based metric of the Freiburg SLAM benchmark (Kuemmerle et al., "On measuring the
/// accuracy of SLAM algorithms", Auton. Robots 2009): errors of relative poses between timestamps.
#include "core/trajectory.hpp"
#include "evaluation/statistics.hpp"

#include <filesystem>
#include <iosfwd>
#include <vector>

namespace revisit {

/// One line `t1 t2 x y z roll pitch yaw`: the pose of the sensor at t2 in its frame at t1.
struct Relation {
    double t1 = 0.0;  ///< [s] in the log's clock
    double t2 = 0.0;  ///< [s]
    Eigen::Isometry3d T_1_2 = Eigen::Isometry3d::Identity();
};

/// Parses a relations file. Blank lines and lines starting with '#' are skipped; anything else that
/// is not 8 numbers throws DatasetError naming `source` and the line.
std::vector<Relation> ParseRelations(std::istream& in, const std::filesystem::path& source);

struct RelationMetricConfig {
    double max_time_difference = 1e-3;  ///< [s] a relation's stamp must match a trajectory stamp this closely
};

struct RelationErrors {
    std::size_t num_used = 0;       ///< relations whose both stamps matched a pose
    std::size_t num_unmatched = 0;  ///< relations skipped: a stamp without a pose
    ErrorStatistics translation;          ///< [m] |translation of E|, E = T_1_2^-1 * (P_t1^-1 P_t2)
    ErrorStatistics translation_squared;  ///< [m^2] as the benchmark also reports
    ErrorStatistics rotation_deg;         ///< [deg] rotation angle of E (|yaw error| for planar data)
    ErrorStatistics rotation_deg_squared; ///< [deg^2]
};

/// Needs `trajectory.timestamps`; each relation stamp takes the pose of the nearest stamp.
/// Evaluate the corrected trajectory and the odometry with the same relations to compare them.
RelationErrors EvaluateRelations(const Trajectory& trajectory, const std::vector<Relation>& relations,
                                 const RelationMetricConfig& config = {});

}  // namespace revisit
