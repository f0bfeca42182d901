#include "io/carmen_line.hpp"

#include <charconv>
#include <cmath>
#include <cstdlib>
#include <sstream>
#include <stdexcept>

namespace revisit {
namespace {

/// Splits on blanks; views into `line`.
std::vector<std::string_view> Tokens(std::string_view line) {
    std::vector<std::string_view> tokens;
    std::size_t i = 0;
    while (i < line.size()) {
        while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r')) ++i;
        const std::size_t begin = i;
        while (i < line.size() && line[i] != ' ' && line[i] != '\t' && line[i] != '\r') ++i;
        if (i > begin) tokens.push_back(line.substr(begin, i - begin));
    }
    return tokens;
}

class Fields {
  public:
    Fields(std::vector<std::string_view> tokens, std::string_view name) : tokens_(std::move(tokens)), name_(name) {}
    std::size_t left() const { return tokens_.size() - next_; }
    double Number(const char* what) {
        if (next_ >= tokens_.size()) Fail(std::string("ends before ") + what);
        // The fast path (no copy, no locale; a log holds ~80 ODOM lines per scan): the shortest
        // exact reading, the same value strtod gives; anything it declines ('+1', an underflow)
        // takes strtod below.
        const std::string_view token = tokens_[next_];
        double fast = 0.0;
        const auto [ptr, ec] = std::from_chars(token.data(), token.data() + token.size(), fast);
        if (ec == std::errc() && ptr == token.data() + token.size() && std::isfinite(fast)) {
            ++next_;
            return fast;
        }
        const std::string text(token);
        char* end = nullptr;
        // An underflow (a subnormal such as 5e-312, found in orebro's ODOM lines) reads as itself or 0;
        // an overflow reads as inf and is refused below.
        const double value = std::strtod(text.c_str(), &end);
        if (end == text.c_str() || *end != '\0' || !std::isfinite(value)) {
            Fail(std::string(what) + " (field " + std::to_string(next_ + 1) + ") is not a finite number: '" + text.substr(0, 40) + "'");
        }
        ++next_;
        return value;
    }
    /// A count that must fit in the fields left (so nothing is allocated for a damaged count).
    std::size_t Count(const char* what) {
        const double value = Number(what);
        if (value < 0 || value != std::floor(value) || value > static_cast<double>(left())) {
            std::ostringstream problem;
            problem << what << " " << value << " is not a count of the " << left() << " fields that follow";
            Fail(problem.str());
        }
        return static_cast<std::size_t>(value);
    }
    Pose2 Pose(const char* what) {
        Pose2 p;
        p.x = Number(what);
        p.y = Number(what);
        p.theta = Number(what);
        return p;
    }
    [[noreturn]] void Fail(const std::string& problem) const {
        throw std::invalid_argument(std::string(name_) + " line: " + problem);
    }

  private:
    std::vector<std::string_view> tokens_;
    std::string_view name_;
    std::size_t next_ = 1;
};

}  // namespace

bool IsCarmenMessageName(std::string_view name) {
    for (const char* known : {"PARAM", "SYNC", "ODOM", "FLASER", "RLASER", "LASER3", "LASER4", "ROBOTLASER1", "ROBOTLASER2",
                              "RAWLASER1", "RAWLASER2", "RAWLASER3", "RAWLASER4", "TRUEPOS", "NMEAGGA", "NMEARMC", "SONAR",
                              "BUMPER", "SCANMARK", "POSITIONLASER", "IMU", "VECTORMOVE", "ROBOTVELOCITY", "FOLLOWTRAJECTORY",
                              "BASEVELOCITY", "NEFF"}) {
        if (name == known) return true;
    }
    return false;
}

CarmenLineKind ParseCarmenLine(std::string_view line, std::string& name, CarmenLaser& laser, CarmenOdom& odom) {
    auto tokens = Tokens(line);
    if (tokens.empty() || tokens.front().front() == '#') return CarmenLineKind::kBlank;
    name.assign(tokens.front());
    Fields f(std::move(tokens), name);
    if (name == "FLASER" || name == "RLASER") {
        // FLASER n r_1 .. r_n x y theta odom_x odom_y odom_theta [ipc_timestamp ipc_hostname logger_timestamp]
        laser = CarmenLaser{};
        laser.kind = name;
        const std::size_t n = f.Count("the number of readings");
        laser.ranges.reserve(n);
        for (std::size_t i = 0; i < n; ++i) laser.ranges.push_back(f.Number("a range"));
        laser.laser = f.Pose("the laser pose");
        laser.robot = f.Pose("the robot pose");
        if (f.left() > 0) laser.timestamp = f.Number("the timestamp");
        return CarmenLineKind::kLaser;
    }
    if (name == "ROBOTLASER1") {
        // ROBOTLASER1 laser_type start_angle fov angular_resolution max_range accuracy remission_mode
        //   n r_1 .. r_n m e_1 .. e_m laser_x laser_y laser_theta robot_x robot_y robot_theta
        //   tv rv forward_safety_dist side_safety_dist turn_axis ipc_timestamp ipc_hostname logger_timestamp
        laser = CarmenLaser{};
        laser.kind = name;
        laser.stated_geometry = true;
        f.Number("the laser type");
        laser.start_angle = f.Number("the start angle");
        laser.fov = f.Number("the field of view");
        laser.resolution = f.Number("the angular resolution");
        laser.max_range = f.Number("the maximum range");
        f.Number("the accuracy");
        f.Number("the remission mode");
        const std::size_t n = f.Count("the number of readings");
        laser.ranges.reserve(n);
        for (std::size_t i = 0; i < n; ++i) laser.ranges.push_back(f.Number("a range"));
        const std::size_t m = f.Count("the number of remissions");
        for (std::size_t i = 0; i < m; ++i) f.Number("a remission");
        laser.laser = f.Pose("the laser pose");
        laser.robot = f.Pose("the robot pose");
        for (const char* what : {"tv", "rv", "forward_safety_dist", "side_safety_dist", "turn_axis"}) f.Number(what);
        laser.timestamp = f.Number("the timestamp");
        if (!(laser.resolution >= 0.0) || !(laser.fov >= 0.0) || !(laser.max_range > 0.0)) {
            f.Fail("angular resolution, field of view and maximum range must be positive");
        }
        return CarmenLineKind::kLaser;
    }
    if (name == "ODOM") {
        // ODOM x y theta tv rv accel [ipc_timestamp ipc_hostname logger_timestamp]
        odom = CarmenOdom{};
        odom.pose = f.Pose("the pose");
        for (const char* what : {"tv", "rv", "accel"}) f.Number(what);
        if (f.left() > 0) odom.timestamp = f.Number("the timestamp");
        return CarmenLineKind::kOdom;
    }
    return CarmenLineKind::kOther;
}

}  // namespace revisit
