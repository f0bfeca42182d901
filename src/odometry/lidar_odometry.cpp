#include "odometry/lidar_odometry.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <functional>
#include <limits>
#include <sstream>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>
#include <tbb/parallel_reduce.h>

#include "core/error.hpp"
#include "odometry/correlative_matcher.hpp"
#include "odometry/preprocess.hpp"
#include "odometry/registration.hpp"

namespace revisit {
namespace {

constexpr std::size_t kAgreementSamples = 500;  ///< points checked for the agreement share
/// Registrations with measured motion (the adaptive threshold's samples) before the map of the first
/// scans covers the ground between its rings: with fewer, 3D frames register point-to-plane.
constexpr std::size_t kMotionsMeasuredAtStart = 3;

const OdometryConfig& Validated(const OdometryConfig& config) {
    auto require = [](bool ok, const char* what) {
        if (!ok) throw ConfigError(std::string("odometry: ") + what);
    };
    require(config.max_range > 0.0 && std::isfinite(config.max_range), "max_range must be positive");
    require(config.min_range >= 0.0 && config.min_range < config.max_range, "min_range must be in [0, max_range)");
    require(config.voxel_size >= 0.0, "voxel_size must be >= 0 (0: max_range / 100)");
    // The map reserves max_points_per_voxel slots per voxel (contiguous search): bound the memory.
    require(config.max_points_per_voxel >= 1 && config.max_points_per_voxel <= 100,
            "max_points_per_voxel must be in [1, 100]");
    require(config.initial_threshold > 0.0, "initial_threshold must be positive");
    require(config.min_motion_th >= 0.0, "min_motion_th must be >= 0");
    require(config.max_iterations >= 1, "max_iterations must be >= 1");
    require(config.convergence > 0.0, "convergence must be positive");
    require(config.max_correction > 0.0, "max_correction must be positive");
    require(config.degenerate_thickness >= 0.0, "degenerate_thickness must be >= 0");
    require(config.prior_bias_window > 0.0, "prior_bias_window must be positive");
    require(config.map_travel_horizon >= 0.0, "map_travel_horizon must be >= 0 (0: off)");
    return config;
}

/// Products of poses slowly lose orthonormality, and T^-1 (which assumes it) then amplifies the
/// loss frame after frame: re-project the rotation every frame.
Eigen::Isometry3d Orthonormalized(const Eigen::Isometry3d& T) {
    Eigen::Isometry3d clean = T;
    clean.linear() = Eigen::Quaterniond(T.linear()).normalized().toRotationMatrix();
    return clean;
}

std::string Describe(double value) {
    std::ostringstream out;
    out << value;
    return out.str();
}

}  // namespace

LidarOdometry::LidarOdometry(const OdometryConfig& config)
    : config_(Validated(config)),
      map_(config.VoxelSize(), config.max_points_per_voxel),
      recent_map_(config.VoxelSize(), config.max_points_per_voxel),
      threshold_(config.initial_threshold, config.min_motion_th, config.max_range),
      prior_bias_(PriorBiasConfig{config.prior_bias_correction, config.prior_bias_window}) {
    // 2D scans have no planes in the map (a wall is a line): they stay point-to-point. With ring_start a
    // 3D map keeps normals until the motion is measured (MotionUnmeasured, RegisterFrom).
    map_.EnableNormals(config.residual == IcpResidual::kPointToPlane || (config.ring_start && !config.planar), config.planar);
    recent_map_.EnableNormals(config.residual == IcpResidual::kPointToPlane, config.planar);
}

void LidarOdometry::SetMaxRange(double max_range) {
    config_ = Validated(WithMaxRange(config_, max_range));
    threshold_.SetMaxRange(max_range);
}

bool LidarOdometry::MotionUnmeasured() const {
    return config_.ring_start && !config_.planar && !stats_.prior_used && threshold_.NumSamples() < kMotionsMeasuredAtStart;
}

Eigen::Isometry3d LidarOdometry::PredictMotion(const Scan& scan) {
    if (config_.use_prior && scan.T_odom_sensor && last_T_odom_sensor_) {
        stats_.prior_used = true;
        raw_prior_delta_ = last_T_odom_sensor_->inverse() * *scan.T_odom_sensor;
        stats_.prior_heading_bias = prior_bias_.RatePerMetre().z();
        return prior_bias_.Correct(raw_prior_delta_);
    }
    return last_delta_;
}

std::string LidarOdometry::DegeneracyReason(const std::vector<Eigen::Vector3d>& points) const {
    const std::size_t min_points = static_cast<std::size_t>(std::max(config_.min_correspondences, 3));
    if (points.size() < min_points) {
        return "only " + std::to_string(points.size()) + " points left in [" + Describe(config_.min_range) + ", " +
               Describe(config_.max_range) + "] m after downsampling";
    }
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    for (const auto& p : points) mean += p;
    mean /= static_cast<double>(points.size());
    Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
    for (const auto& p : points) covariance.noalias() += (p - mean) * (p - mean).transpose();
    covariance /= static_cast<double>(points.size());
    // Planar scans constrain x, y, yaw unless they are collinear; 3D scans need more than a plane.
    const double smallest = config_.planar
                                ? Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(covariance.topLeftCorner<2, 2>()).eigenvalues()[0]
                                : Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(covariance).eigenvalues()[0];
    const double thickness = std::sqrt(std::max(smallest, 0.0));
    if (thickness < config_.degenerate_thickness) {
        return std::string("the points lie on a single ") + (config_.planar ? "line" : "plane") + " (spread " +
               Describe(thickness) + " m): motion unobservable";
    }
    return {};
}

std::size_t LidarOdometry::CountAgreeing(const VoxelHashMap& map, const std::vector<Eigen::Vector3d>& source,
                                         const Eigen::Isometry3d& T_world_sensor, double radius, std::size_t stride) const {
    // An integer sum: the same at any thread count.
    const std::size_t samples = (source.size() + stride - 1) / stride;
    const std::size_t count = tbb::parallel_reduce(
        tbb::blocked_range<std::size_t>(0, samples, 512), std::size_t{0},
        [&](const tbb::blocked_range<std::size_t>& range, std::size_t sum) {
            for (std::size_t k = range.begin(); k != range.end(); ++k)
                sum += map.FindNearest(T_world_sensor * source[k * stride], radius) != nullptr;
            return sum;
        },
        std::plus<>());
    return count * stride;
}

double LidarOdometry::CorrectionLimit() const {
    // Before any frame: the initial threshold stands for the expected correction.
    const double rms = num_corrections_ == 0 ? config_.initial_threshold
                                             : std::sqrt(sum_squared_corrections_ / static_cast<double>(num_corrections_));
    return config_.max_correction_factor * std::max({rms, config_.VoxelSize(), config_.min_motion_th});
}

void LidarOdometry::ApplyMapUpdate() {
    if (!map_update_pending_) return;
    map_.SetStamp(map_update_travel_);
    map_.AddPoints(points_in_world_);
    const double horizon = config_.map_travel_horizon;
    map_.RemoveFarFrom(map_update_origin_, map_update_radius_,
                       horizon > 0.0 ? map_update_travel_ - horizon : -std::numeric_limits<double>::infinity());
    if (recent_check_active_) {
        recent_map_.SetStamp(map_update_travel_);
        recent_map_.AddPoints(points_in_world_);
        recent_map_.RemoveFarFrom(map_update_origin_, map_update_radius_, map_update_travel_ - config_.max_range);
    }
    if (free_space_) {
        free_space_->AddBeams(map_update_origin_, points_in_world_, 2.0 * config_.VoxelSize());
        free_space_->RemoveFarFrom(map_update_origin_, map_update_radius_);
    }
    map_update_pending_ = false;
}

const VoxelHashMap& LidarOdometry::LocalMap() {
    ApplyMapUpdate();
    return map_;
}

Eigen::Isometry3d LidarOdometry::CorrelativeStart(const VoxelHashMap& map, const std::vector<Eigen::Vector3d>& source, const Eigen::Isometry3d& last_pose,
                                                  const Eigen::Isometry3d& delta, double& resolution) {
    CorrelativeMatchConfig match_config;
    // Between the peaks of a corridor's likelihood (the true step and one a metre or two along it) the
    // scores differ by ~2%, while a pose half a cell off the grid loses 12% at one-voxel cells with a
    // one-cell kernel: the search picked whichever peak the grid happened to sample well (orebro).
    // Half-voxel cells with the same one-voxel kernel (2 cells) lose 3%, and every map point is drawn
    // (one point per voxel would leave the walls dotted at half-voxel cells).
    // With wheel odometry the match only restarts a failed ICP near the prior: one-voxel cells as before.
    const bool fine = !stats_.prior_used;
    match_config.resolution = (fine ? 0.5 : 1.0) * config_.VoxelSize();
    match_config.kernel_sigma_cells = fine ? 2.0 : 1.0;
    match_config.linear_window = config_.correlative_window;
    // The retry over twice the window keeps the pull's strength per metre: it adds poses, it does not
    // weaken the tie-break between a corridor's equal peaks.
    match_config.prior_distance = config_.correlative_window;
    // Without wheel odometry, the heading is what is known of the motion: along a corridor the poses one
    // door spacing back or sideways explain the scan as well as the true step forward (orebro).
    if (fine && config_.correlative_heading_prior) {
        match_config.heading_prior = true;
        match_config.heading_origin = last_pose.translation().head<2>();
        match_config.heading_yaw = std::atan2(last_pose.linear()(1, 0), last_pose.linear()(0, 0));
    }
    // Key frames turn one way and then back: the rotations searched span both the predicted turn and
    // none, and the window beyond either.
    const double predicted_turn = std::atan2(delta.linear()(1, 0), delta.linear()(0, 0));
    match_config.angular_window = config_.correlative_angular_window_deg * M_PI / 180.0 + 0.5 * std::abs(predicted_turn);
    Eigen::Isometry3d half_turn = Eigen::Isometry3d::Identity();
    half_turn.translation() = delta.translation();
    half_turn.linear() = Eigen::AngleAxisd(0.5 * predicted_turn, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    const Eigen::Isometry3d T_centre = ProjectToPlanar(Orthonormalized(last_pose * half_turn));
    // The map within reach of any searched pose: every point for the fine grid, else one per voxel.
    const auto gather = [&](double window) {
        reference_.clear();
        if (fine)
            map.AllPointsNear(T_centre.translation(), config_.max_range + window, reference_);
        else
            map.PointsNear(T_centre.translation(), config_.max_range + window, reference_);
    };
    gather(config_.correlative_window);
    CorrelativeMatch match = MatchCorrelative2D(reference_, source, T_centre, match_config);
    // A best pose on the window's border says the motion may lie beyond it (a spin in place, a long
    // step): the search is repeated over twice the windows, and the better match kept.
    if (match.valid && match.at_edge) {
        CorrelativeMatchConfig wider = match_config;
        wider.linear_window *= 2.0;
        wider.angular_window = std::min(2.0 * wider.angular_window, M_PI);
        gather(wider.linear_window);
        const CorrelativeMatch retry = MatchCorrelative2D(reference_, source, T_centre, wider);
        // A better score alone does not decide: a room turned by 90 deg, or a corridor's alias, may explain
        // more returns than the true pose, whose scan looks into new territory (orebro scan 48 with 3 cm
        // of range noise). Such a pose puts returns where earlier beams passed and beams through mapped
        // walls: the retry is kept only when it contradicts the beams no more than the first match.
        bool take = retry.valid && retry.score > match.score;
        if (take && free_space_) {
            const double margin = 2.0 * config_.VoxelSize();
            const auto first = CountBeamConflicts(*free_space_, map, source, match.T_world_sensor, margin).Total();
            const auto wider_conflicts = CountBeamConflicts(*free_space_, map, source, retry.T_world_sensor, margin).Total();
            take = !ClearlyMore(static_cast<double>(wider_conflicts), static_cast<double>(first));
        }
        if (take) match = retry;
    }
    stats_.correlative_used = match.valid;
    stats_.correlative_score = match.score;
    resolution = match.valid ? match.resolution : 0.0;
    return match.valid ? match.T_world_sensor : ProjectToPlanar(Orthonormalized(last_pose * delta));
}

std::string LidarOdometry::RegisterFrom(const VoxelHashMap& map, const std::vector<Eigen::Vector3d>& source, const Eigen::Isometry3d& T_start,
                                        const Eigen::Isometry3d& delta, const Eigen::Isometry3d& last_pose, bool turn_hypothesis,
                                        double start_resolution, Eigen::Isometry3d& T_new) {
    const double voxel = config_.VoxelSize();
    // From a correlative match the start is off by about its cell, whatever the motion was.
    const double sigma = std::max(threshold_.Sigma(), start_resolution);
    IcpParams params;
    params.max_correspondence_distance = 3.0 * sigma;
    params.kernel = config_.kernel == IcpKernel::kPaper ? sigma / 3.0 : sigma;
    params.max_iterations = config_.max_iterations;
    params.convergence = config_.convergence;
    params.anderson_depth = config_.anderson_depth;
    params.min_correspondences = config_.min_correspondences;
    params.planar = config_.planar;
    // Until the motion is measured, ICP starts from zero motion or from one measured step, on a map
    // of the first scans alone, whose ground is sampled only along their rings: each ring of the new
    // scan snaps onto the same ring of the last scan, and point-to-point residuals pull a moving start
    // back to standing still (a drive recorded at 3 m/s lost 2.7 m over its first 9 scans). Along the
    // ground's normal that pull vanishes and the structure decides the step.
    params.point_to_plane = config_.residual == IcpResidual::kPointToPlane || MotionUnmeasured();
    IcpResult icp = RegisterPointsToMap(source, map, T_start, params);
    // The agreement check needs a share, not a count: every k-th point of ~500 is enough and keeps
    // its cost a fraction of one ICP iteration. Comparing two hypotheses counts every point.
    const std::size_t stride = std::max<std::size_t>(1, source.size() / kAgreementSamples);
    std::size_t agreeing = icp.valid ? CountAgreeing(map, source, icp.T_world_sensor, voxel, stride) : 0;
    // A swaying sensor (handheld, legged) reverses its turns between scans, so constant velocity
    // can predict the rotation wrongly by more than ICP's basin. When the predicted turn moves
    // points by more than a voxel, also register from the translation-only prediction and keep
    // the result more points agree with (within one voxel of the map). Only for extrapolated
    // motion: a wheel-odometry prior measures the turn.
    Eigen::Isometry3d delta_translation = delta;
    delta_translation.linear().setIdentity();
    if (turn_hypothesis && config_.turn_hypothesis && !poses_.empty() && !stats_.prior_used &&
        ModelError(delta_translation.inverse() * delta, config_.max_range) > voxel) {
        const IcpResult alternative = RegisterPointsToMap(source, map, Orthonormalized(last_pose * delta_translation), params);
        const std::size_t alternative_agreeing =
            alternative.valid && alternative.T_world_sensor.matrix().allFinite() ? CountAgreeing(map, source, alternative.T_world_sensor, voxel, 1) : 0;
        if (icp.valid) agreeing = CountAgreeing(map, source, icp.T_world_sensor, voxel, 1);
        if (alternative_agreeing > agreeing) {
            icp = alternative;
            agreeing = alternative_agreeing;
            stats_.turn_hypothesis_used = true;
        }
    }
    stats_.agreement = source.empty() ? 0.0 : std::min(1.0, static_cast<double>(agreeing) / static_cast<double>(source.size()));
    stats_.iterations = icp.iterations;
    stats_.correspondences = icp.correspondences;
    stats_.plane_correspondences = icp.plane_correspondences;
    stats_.planes_only = icp.planes_only;
    // A correction is judged by its translation: the rotation part of the model error grows with
    // max_range, and a swaying handheld sensor turns 15 deg between keyframes legitimately.
    const double correction = (T_start.inverse() * icp.T_world_sensor).translation().norm();
    if (!icp.valid) {
        return "only " + std::to_string(icp.correspondences) + " correspondences within " + Describe(params.max_correspondence_distance) +
               " m of the map";
    }
    if (!icp.T_world_sensor.matrix().allFinite() || !(correction <= config_.max_correction))
        return "ICP diverged (correction of " + Describe(correction) + " m)";
    if (stats_.agreement < config_.min_agreement) {
        return "only " + Describe(100.0 * stats_.agreement) + "% of the points lie within a voxel of the map after ICP (minimum " +
               Describe(100.0 * config_.min_agreement) + "%): not the scene the map shows";
    }
    if (config_.max_correction_factor > 0.0 && correction > CorrectionLimit()) {
        return "ICP jumped " + Describe(correction) + " m from the motion prediction (limit " + Describe(CorrectionLimit()) +
               " m: " + Describe(config_.max_correction_factor) + " x the RMS of earlier corrections)";
    }
    T_new = config_.planar ? ProjectToPlanar(icp.T_world_sensor) : Orthonormalized(icp.T_world_sensor);
    return {};
}

Eigen::Isometry3d LidarOdometry::RegisterScan(const Scan& scan) { return RegisterPrepared(scan, PrepareScan(scan, config_)); }

Eigen::Isometry3d LidarOdometry::RegisterPrepared(const Scan& scan, PreparedScan prepared) {
    // Prepared ahead with other settings (a caller that changed the range since): prepared again.
    if (!prepared.PreparedFor(config_)) prepared = PrepareScan(scan, config_);
    stats_ = OdometryFrameStats{};
    stats_.input_points = scan.points.size();
    // A 2D laser logged without wheel odometry keeps the map of its recent travel alongside (CheckRecentTravel)
    // and where its beams passed (the beam check of a wider correlative search).
    if (poses_.empty()) {
        const bool laser_alone = config_.planar && config_.correlative_start && !(config_.use_prior && scan.T_odom_sensor);
        recent_check_active_ = laser_alone && config_.recent_travel_check;
        if (laser_alone && config_.beam_check) free_space_.emplace(config_.VoxelSize());
    }
    const Eigen::Isometry3d last_pose = poses_.empty() ? Eigen::Isometry3d::Identity() : poses_.back();
    const Eigen::Isometry3d delta = poses_.empty() ? Eigen::Isometry3d::Identity() : PredictMotion(scan);
    Eigen::Isometry3d T_predicted = Orthonormalized(last_pose * delta);
    if (config_.planar) T_predicted = ProjectToPlanar(T_predicted);

    // Preprocessing, METHOD.md section 1: crop, deskew, downsample at 0.5 v and 1.5 v. PrepareScan did
    // what does not depend on the motion; with deskewing, the deskew and both downsamplings run here,
    // serially, while the previous frame's map update runs alongside (they share no data; both are done
    // before ICP reads the map). Data-parallel versions of the crop and the downsampling (flags,
    // compaction, a merge of per-chunk voxel sets) cost twice the serial work (README "Seventh round").
    deskewed_ = std::move(prepared.cropped);
    if (config_.deskew) {
        const auto preprocess = [&] {
            if (!poses_.empty()) deskewed_ = Deskew(deskewed_, prepared.sweep_times, delta);
            downsampled_ = VoxelDownsample(deskewed_, 0.5 * config_.VoxelSize());
            source_ = VoxelDownsample(downsampled_, 1.5 * config_.VoxelSize());
        };
        if (map_update_pending_)
            tbb::parallel_invoke([&] { ApplyMapUpdate(); }, preprocess);
        else
            preprocess();
    } else {
        downsampled_ = std::move(prepared.downsampled);
        source_ = std::move(prepared.source);
        ApplyMapUpdate();
    }
    stats_.cropped_points = deskewed_.size();
    const std::vector<Eigen::Vector3d>& source = source_;
    stats_.map_points = downsampled_.size();
    stats_.source_points = source.size();

    const double sigma = threshold_.Sigma();
    stats_.sigma = sigma;
    std::string problem = DegeneracyReason(source);
    Eigen::Isometry3d T_new = T_predicted;
    Eigen::Isometry3d T_start = T_predicted;  // where the ICP started: the threshold measures its error
    if (problem.empty() && !map_.Empty()) {
        // A 2D laser without wheel odometry moves between key frames by more than ICP's basin: every
        // frame starts from a correlative match around the prediction. With a prior, only a frame whose
        // ICP failed gets one (the prior is usually right, and the match costs more than the ICP).
        const bool correlative = config_.planar && config_.correlative_start && !poses_.empty();
        const bool correlative_first = correlative && !stats_.prior_used;
        double resolution = 0.0;
        if (correlative_first) T_start = CorrelativeStart(map_, source, last_pose, delta, resolution);
        problem = RegisterFrom(map_, source, T_start, delta, last_pose, !correlative_first, resolution, T_new);
        if (problem.empty() && correlative_first && recent_check_active_) CheckRecentTravel(source, last_pose, delta, T_start, T_new);
        if (!problem.empty() && correlative && !correlative_first) {
            const Eigen::Isometry3d T_match = CorrelativeStart(map_, source, last_pose, delta, resolution);
            const OdometryFrameStats first_try = stats_;
            Eigen::Isometry3d T_retry = T_predicted;
            if (RegisterFrom(map_, source, T_match, delta, last_pose, false, resolution, T_retry).empty()) {
                problem.clear();
                T_new = T_retry;
                T_start = T_match;
            } else {
                stats_ = first_try;  // report the first failure
            }
        }
    }

    if (!problem.empty()) {
        stats_.degenerate = true;
        stats_.warning = "scan " + std::to_string(scan.index) + ": " + problem + "; pose predicted " +
                         (stats_.prior_used ? "from the odometry prior" : "by constant velocity");
        ++num_degenerate_;
    } else {
        threshold_.Update(T_start.inverse() * T_new);
        if (stats_.prior_used) prior_bias_.Update(raw_prior_delta_, last_pose.inverse() * T_new);
        const double correction = (T_start.inverse() * T_new).translation().norm();
        sum_squared_corrections_ += correction * correction;
        ++num_corrections_;
        points_in_world_.resize(downsampled_.size());
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, downsampled_.size(), 8192), [&](const auto& range) {
            for (std::size_t i = range.begin(); i != range.end(); ++i) points_in_world_[i] = T_new * downsampled_[i];
        });
        map_update_pending_ = true;  // applied with the next frame's preprocessing (or on LocalMap())
        map_update_origin_ = T_new.translation();
        travel_ += (last_pose.inverse() * T_new).translation().norm();
        map_update_travel_ = travel_;
        map_update_radius_ = config_.max_range;
    }
    last_delta_ = Orthonormalized(last_pose.inverse() * T_new);
    last_T_odom_sensor_ = scan.T_odom_sensor;
    poses_.push_back(T_new);
    // Once the motion is measured, a map of many scans covers the ground between the rings.
    if (config_.residual != IcpResidual::kPointToPlane && !MotionUnmeasured()) map_.EnableNormals(false, config_.planar);
    return T_new;
}

}  // namespace revisit
