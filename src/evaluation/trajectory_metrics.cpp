#include "evaluation/trajectory_metrics.hpp"

#include "core/error.hpp"
#include "core/se3.hpp"

#include <Eigen/SVD>
#include <cmath>
#include <string>

namespace revisit {
namespace {

constexpr double kDegPerRad = 180.0 / M_PI;

void CheckSameLength(const Poses& estimate, const Poses& reference) {
    if (estimate.size() != reference.size())
        throw ConfigError("trajectory metrics: estimate has " + std::to_string(estimate.size()) +
                          " poses, reference " + std::to_string(reference.size()));
}

void Summarize(PoseErrors& errors) {
    errors.translation_stats = ComputeStatistics(errors.translation);
    errors.rotation_deg_stats = ComputeStatistics(errors.rotation_deg);
}

/// The KITTI devkit's rotation error: acos of the clamped (trace - 1) / 2.
double KittiRotationError(const Eigen::Isometry3d& error) {
    const double d = 0.5 * (error.linear().trace() - 1.0);
    return std::acos(std::max(-1.0, std::min(1.0, d)));
}

}  // namespace

Eigen::Isometry3d AlignUmeyama(const Poses& estimate, const Poses& reference) {
    CheckSameLength(estimate, reference);
    Eigen::Isometry3d T_ref_est = Eigen::Isometry3d::Identity();
    if (estimate.empty()) return T_ref_est;
    const double n = static_cast<double>(estimate.size());
    Eigen::Vector3d mean_est = Eigen::Vector3d::Zero(), mean_ref = Eigen::Vector3d::Zero();
    for (std::size_t i = 0; i < estimate.size(); ++i) {
        mean_est += estimate[i].translation();
        mean_ref += reference[i].translation();
    }
    mean_est /= n;
    mean_ref /= n;
    // Umeyama Eq. (38)-(40): covariance, SVD, reflection guard S.
    Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
    for (std::size_t i = 0; i < estimate.size(); ++i)
        covariance += (reference[i].translation() - mean_ref) * (estimate[i].translation() - mean_est).transpose();
    covariance /= n;
    Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
    const Eigen::JacobiSVD<Eigen::Matrix3d> svd(covariance, Eigen::ComputeFullU | Eigen::ComputeFullV);
    if (estimate.size() >= 3 && svd.singularValues()(1) > 1e-12 * std::max(1.0, svd.singularValues()(0))) {
        Eigen::Matrix3d S = Eigen::Matrix3d::Identity();
        if (svd.matrixU().determinant() * svd.matrixV().determinant() < 0.0) S(2, 2) = -1.0;
        R = svd.matrixU() * S * svd.matrixV().transpose();
    }
    T_ref_est.linear() = R;
    T_ref_est.translation() = mean_ref - R * mean_est;
    return T_ref_est;
}

ApeResult ComputeApe(const Poses& estimate, const Poses& reference, bool align) {
    CheckSameLength(estimate, reference);
    ApeResult result;
    if (align) result.T_ref_est = AlignUmeyama(estimate, reference);
    for (std::size_t i = 0; i < estimate.size(); ++i) {
        const Eigen::Isometry3d aligned = result.T_ref_est * estimate[i];
        result.errors.translation.push_back((reference[i].translation() - aligned.translation()).norm());
        result.errors.rotation_deg.push_back(RotationAngle(aligned.inverse() * reference[i]) * kDegPerRad);
    }
    Summarize(result.errors);
    return result;
}

PoseErrors ComputeRpe(const Poses& estimate, const Poses& reference, std::size_t delta_frames) {
    CheckSameLength(estimate, reference);
    if (delta_frames == 0) throw ConfigError("RPE: delta_frames must be >= 1");
    PoseErrors errors;
    for (std::size_t i = 0; i + delta_frames < estimate.size(); i += delta_frames) {
        const std::size_t j = i + delta_frames;
        const Eigen::Isometry3d error = (reference[i].inverse() * reference[j]).inverse() *
                                        (estimate[i].inverse() * estimate[j]);
        errors.translation.push_back(error.translation().norm());
        errors.rotation_deg.push_back(RotationAngle(error) * kDegPerRad);
    }
    Summarize(errors);
    return errors;
}

KittiErrors ComputeKittiErrors(const Poses& estimate, const Poses& reference, const KittiSegmentConfig& config) {
    CheckSameLength(estimate, reference);
    if (config.step_frames == 0) throw ConfigError("KITTI errors: step_frames must be >= 1");
    const std::vector<double> travel = CumulativeDistance(reference);
    KittiErrors result;
    double sum_t = 0.0, sum_r = 0.0;
    for (const double length : config.lengths) {
        KittiLengthError per_length;
        per_length.length = length;
        for (std::size_t first = 0; first < reference.size(); first += config.step_frames) {
            std::size_t last = first;
            while (last < travel.size() && !(travel[last] > travel[first] + length)) ++last;
            if (last >= travel.size()) continue;
            const Eigen::Isometry3d delta_ref = reference[first].inverse() * reference[last];
            const Eigen::Isometry3d delta_est = estimate[first].inverse() * estimate[last];
            const Eigen::Isometry3d error = delta_est.inverse() * delta_ref;
            const double t_err = error.translation().norm() / length;
            const double r_err = KittiRotationError(error) / length;
            ++per_length.num_segments;
            per_length.translation_percent += t_err;
            per_length.rotation_deg_per_100m += r_err;
            sum_t += t_err;
            sum_r += r_err;
        }
        result.num_segments += per_length.num_segments;
        if (per_length.num_segments > 0) {
            per_length.translation_percent *= 100.0 / double(per_length.num_segments);
            per_length.rotation_deg_per_100m *= 100.0 * kDegPerRad / double(per_length.num_segments);
        }
        result.per_length.push_back(per_length);
    }
    if (result.num_segments > 0) {
        result.translation_percent = 100.0 * sum_t / double(result.num_segments);
        result.rotation_deg_per_100m = 100.0 * kDegPerRad * sum_r / double(result.num_segments);
    }
    return result;
}

}  // namespace revisit
