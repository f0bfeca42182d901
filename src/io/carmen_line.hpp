#pragma once
/// One line of a CARMEN log (the text format of the CARMEN robot toolkit and the Radish / Freiburg
/// collections), parsed without state: laser lines (FLASER, RLASER, ROBOTLASER1) and ODOM lines.
#include <string>
#include <string_view>
#include <vector>

namespace revisit {

struct Pose2 {
    double x = 0.0, y = 0.0;  ///< [m]
    double theta = 0.0;       ///< [rad]
};

struct CarmenLaser {
    std::string kind;            ///< "FLASER", "RLASER" or "ROBOTLASER1"
    std::vector<double> ranges;  ///< [m] in beam order
    /// ROBOTLASER1 states its geometry; FLASER/RLASER beams span 180 deg from -90 deg, counter-clockwise.
    bool stated_geometry = false;
    double start_angle = 0.0;   ///< [rad] ROBOTLASER1: angle of the first beam
    double fov = 0.0;           ///< [rad] ROBOTLASER1: field of view
    double resolution = 0.0;    ///< [rad] ROBOTLASER1: angle between beams
    double max_range = 0.0;     ///< [m] ROBOTLASER1: the laser's maximum range
    Pose2 laser;                ///< the laser's pose in the odometry frame (the robot's pose plus the laser offset)
    Pose2 robot;                ///< the robot's pose
    double timestamp = 0.0;     ///< [s] ipc_timestamp; 0 when the line has none
};

struct CarmenOdom {
    Pose2 pose;
    double timestamp = 0.0;  ///< [s]
};

enum class CarmenLineKind { kBlank, kLaser, kOdom, kOther };

/// Parses `line`; fills `laser` or `odom` for those kinds; `name` gets the message name (first
/// word). Throws std::invalid_argument naming the problem (the caller adds the file and line).
CarmenLineKind ParseCarmenLine(std::string_view line, std::string& name, CarmenLaser& laser, CarmenOdom& odom);

/// True for the message names CARMEN logs hold (PARAM, SYNC, ODOM, FLASER, RLASER, ROBOTLASER1,
/// RAWLASER1..4, TRUEPOS, ...): how a file is recognized as a CARMEN log.
bool IsCarmenMessageName(std::string_view name);

}  // namespace revisit
