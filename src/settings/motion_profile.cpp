#include "settings/motion_profile.hpp"

#include <cmath>
#include <iomanip>
#include <sstream>

#include "core/quantile.hpp"

namespace revisit {

bool MotionMeter::Add(const Scan& scan) {
    if (Done()) return false;
    if (scan.points.empty() && !scan.T_odom_sensor) return true;
    if (scans_ == 0) from_prior_ = scan.T_odom_sensor.has_value();
    Eigen::Isometry3d pose;
    if (from_prior_) {
        if (!scan.T_odom_sensor) return true;  // a scan without the prior: skip it, keep the source
        pose = *scan.T_odom_sensor;
    } else {
        if (!odometry_) odometry_.emplace(odometry_config_);
        pose = odometry_->RegisterScan(scan);
    }
    if (scans_ == 0) first_time_ = scan.timestamp;
    ++scans_;
    if (last_pose_) {
        const double dt = scan.timestamp - last_time_;
        // Observations that share a time stamp (a rawlog's odometry and laser) are one step.
        if (!(dt > 0.0)) return !Done();
        const Eigen::Isometry3d delta = last_pose_->inverse() * pose;
        const double step = delta.translation().norm();
        travel_ += step;
        speeds_.push_back(step / dt);
        if (last_step_) turn_changes_.push_back(Eigen::AngleAxisd(last_step_->linear().transpose() * delta.linear()).angle());
        last_step_ = delta;
    }
    last_pose_ = pose;
    last_time_ = scan.timestamp;
    return !Done();
}

bool MotionMeter::Done() const { return scans_ >= max_scans_ || (scans_ > 1 && last_time_ - first_time_ >= max_seconds_); }

MotionProfile MotionMeter::Profile() const {
    MotionProfile profile;
    profile.scans = scans_;
    profile.travel = travel_;
    profile.duration = last_time_ - first_time_;
    if (speeds_.size() < 5) return profile;  // no usable time stamps
    // The 75th percentile: a platform that stands for part of the window still shows its pace.
    profile.speed = Quantile(speeds_, 0.75);
    if (!turn_changes_.empty()) profile.turn_misprediction = Quantile(turn_changes_, 0.9);
    profile.source = from_prior_ ? "odometry prior" : "lidar odometry";
    return profile;
}

std::string MotionProfile::Describe() const {
    std::ostringstream out;
    out << std::fixed << std::setprecision(2);
    if (!known()) {
        out << "speed unknown (" << scans << " scans"
            << (duration > 0.0 ? ", " + std::to_string(static_cast<int>(duration)) + " s without motion" : ", no usable time stamps") << ")";
        return out.str();
    }
    out << "speed " << speed << " m/s (75th percentile over " << scans << " scans, " << std::setprecision(1) << duration
        << " s, " << travel << " m, from the " << source << "); constant-velocity turn off by "
        << std::setprecision(2) << turn_misprediction * 180.0 / M_PI << " deg (90th percentile)";
    return out.str();
}

}  // namespace revisit
