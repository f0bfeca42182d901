#include "settings/data_profile.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <unordered_set>

#include "closures/ground_alignment.hpp"
#include "core/quantile.hpp"
#include "core/voxel.hpp"

namespace revisit {
namespace {

/// Points kept per scan for the percentiles: enough for 1% quantiles, cheap for 125k-point scans.
constexpr std::size_t kSamplesPerScan = 4096;

std::string Fixed(double value, int digits) {
    std::ostringstream out;
    out << std::fixed << std::setprecision(digits) << value;
    return out.str();
}

/// [deg] elevation histogram bin for finding rings: finer than any spinning sensor's ring step (HDL-64: ~0.4).
constexpr double kElevationBinDeg = 0.1;

/// Scans whose downsampled size is counted (a full pass over their points per candidate).
constexpr std::size_t kVoxelCountScans = 5;

std::size_t OccupiedVoxels(const std::vector<Eigen::Vector3f>& points, double voxel) {
    std::unordered_set<Voxel, VoxelHash> occupied;
    occupied.reserve(points.size() / 4);
    for (const auto& p : points) {
        // A point beyond any sensor's reach is damage (named by the profile); its voxel index would overflow.
        if (p.allFinite() && p.cast<double>().norm() <= kMaxPlausibleRange) occupied.insert(VoxelOf(p.cast<double>(), voxel));
    }
    return occupied.size();
}

/// Distinct elevation rings in a histogram of elevations (bins of kElevationBinDeg from -90 deg), within
/// [low, high] [deg]: runs of bins that hold at least a tenth of the uniform density. 0 when most bins
/// are occupied (no distinct rings: a rosette or another non-repetitive pattern).
int CountRings(const std::vector<std::size_t>& histogram, double low, double high) {
    const auto first = static_cast<std::size_t>(std::clamp((low + 90.0) / kElevationBinDeg, 0.0, double(histogram.size() - 1)));
    const auto last = static_cast<std::size_t>(std::clamp((high + 90.0) / kElevationBinDeg, 0.0, double(histogram.size() - 1)));
    if (last <= first) return 0;
    const std::size_t bins = last - first + 1;
    std::size_t inside = 0;
    for (std::size_t b = first; b <= last; ++b) inside += histogram[b];
    const double min_count = std::max(1.0, 0.1 * static_cast<double>(inside) / static_cast<double>(bins));
    std::size_t occupied = 0;
    int rings = 0;
    for (std::size_t b = first; b <= last; ++b) {
        const bool on = static_cast<double>(histogram[b]) >= min_count;
        occupied += on;
        rings += on && (b == first || static_cast<double>(histogram[b - 1]) < min_count);
    }
    return 2 * occupied > bins ? 0 : rings;
}

}  // namespace

const std::vector<double>& VoxelCandidates() {
    static const std::vector<double> candidates = {0.05, 0.1, 0.15, 0.2, 0.25, 0.3, 0.4, 0.5, 0.6, 0.75, 1.0};
    return candidates;
}

void DataProfiler::NoteFarPoint(const Scan& scan, double range) {
    if (range > kMaxPlausibleRange && far_range_ == 0.0) {
        far_scan_ = scan.index;
        far_range_ = range;
    }
}

bool DataProfiler::Add(const Scan& scan) {
    if (Done()) return false;
    if (scan.points.empty()) return true;
    ++scans_;
    points_per_scan_.push_back(static_cast<double>(scan.points.size()));
    timestamps_.push_back(scan.timestamp);
    point_times_ = point_times_ || scan.has_point_times();
    odometry_prior_ = odometry_prior_ || scan.T_odom_sensor.has_value();
    if (scans_ <= kVoxelCountScans) {
        source_points_.resize(VoxelCandidates().size());
        for (std::size_t k = 0; k < VoxelCandidates().size(); ++k) {
            source_points_[k].push_back(static_cast<double>(OccupiedVoxels(scan.points, 1.5 * VoxelCandidates()[k])));
        }
        // Rings from every point: a strided sample can alias with the beam order (every 4th of 64 rings).
        elevation_histogram_.resize(static_cast<std::size_t>(180.0 / kElevationBinDeg) + 1, 0);
        for (const auto& point : scan.points) {
            const double range = point.cast<double>().norm();
            if (!(range > 0.0) || !std::isfinite(range)) continue;
            NoteFarPoint(scan, range);
            const double elevation = std::asin(std::clamp(double(point.z()) / range, -1.0, 1.0)) * 180.0 / M_PI;
            ++elevation_histogram_[static_cast<std::size_t>((elevation + 90.0) / kElevationBinDeg)];
        }
        const GroundAlignment ground = AlignGround(scan.points, GroundAlignmentConfig{});
        if (ground.aligned) {
            const double cos_tilt = std::clamp(ground.T_ground_map.linear()(2, 2), -1.0, 1.0);
            ground_tilts_.push_back(std::acos(cos_tilt) * 180.0 / M_PI);
        }
    }
    const std::size_t stride = std::max<std::size_t>(1, scan.points.size() / kSamplesPerScan);
    for (std::size_t i = 0; i < scan.points.size(); i += stride) {
        const Eigen::Vector3d p = scan.points[i].cast<double>();
        const double range = p.norm();
        if (!(range > 0.0) || !std::isfinite(range)) continue;
        NoteFarPoint(scan, range);
        if (p.z() != 0.0) planar_ = false;
        ranges_.push_back(range);
        elevations_.push_back(std::asin(std::clamp(p.z() / range, -1.0, 1.0)) * 180.0 / M_PI);
        const double azimuth = std::atan2(p.y(), p.x()) * 180.0 / M_PI + 180.0;
        azimuth_bins_[static_cast<std::size_t>(std::clamp(azimuth, 0.0, 359.999))] = true;
    }
    return !Done();
}

DataProfile DataProfiler::Profile() const {
    DataProfile profile;
    profile.scans = scans_;
    if (scans_ == 0) return profile;
    profile.planar = planar_;
    profile.points_per_scan = Quantile(points_per_scan_, 0.5);
    profile.range_p01 = Quantile(ranges_, 0.01);
    profile.range_p50 = Quantile(ranges_, 0.5);
    profile.range_p95 = Quantile(ranges_, 0.95);
    profile.range_p99 = Quantile(ranges_, 0.99);
    profile.range_max = ranges_.empty() ? 0.0 : *std::max_element(ranges_.begin(), ranges_.end());
    profile.far_scan = far_scan_;
    profile.far_range = far_range_;
    profile.horizontal_fov_deg = static_cast<double>(std::count(azimuth_bins_.begin(), azimuth_bins_.end(), true));
    profile.vertical_fov_deg = planar_ ? 0.0 : Quantile(elevations_, 0.99) - Quantile(elevations_, 0.01);
    if (!planar_) {
        profile.rings = CountRings(elevation_histogram_, Quantile(elevations_, 0.01), Quantile(elevations_, 0.99));
        if (profile.rings > 1) profile.ring_spacing_deg = profile.vertical_fov_deg / (profile.rings - 1);
    }
    std::vector<double> periods;
    for (std::size_t i = 1; i < timestamps_.size(); ++i) {
        const double dt = timestamps_[i] - timestamps_[i - 1];
        if (dt > 0.0) periods.push_back(dt);
    }
    profile.scan_period = Quantile(periods, 0.5);
    profile.has_point_times = point_times_;
    profile.has_odometry_prior = odometry_prior_;
    profile.voxel_candidates = VoxelCandidates();
    for (const auto& counts : source_points_) profile.source_points.push_back(Quantile(counts, 0.5));
    if (!planar_ && !ground_tilts_.empty()) profile.ground_tilt_deg = Quantile(ground_tilts_, 0.5);
    return profile;
}

std::vector<std::string> DataProfile::Describe() const {
    if (empty()) return {"no scan with points"};
    std::vector<std::string> lines;
    lines.push_back(std::string(planar ? "2D laser" : "3D") + ", " + Fixed(points_per_scan, 0) + " points per scan (median of " +
                    std::to_string(scans) + " scans)");
    lines.push_back("ranges: 1% " + Fixed(range_p01, 2) + " m, median " + Fixed(range_p50, 2) + " m, 95% " + Fixed(range_p95, 1) +
                    " m, 99% " + Fixed(range_p99, 1) + " m, max " + Fixed(range_max, 1) + " m");
    std::string fov = "field of view: " + Fixed(horizontal_fov_deg, 0) + " deg horizontal";
    if (!planar) fov += ", " + Fixed(vertical_fov_deg, 1) + " deg vertical (1-99% of the points)";
    if (!planar) fov += rings > 1 ? ", " + std::to_string(rings) + " rings " + Fixed(ring_spacing_deg, 2) + " deg apart" : ", no distinct rings";
    lines.push_back(fov);
    std::string timing = scan_period > 0.0 ? "scan period " + Fixed(scan_period, 3) + " s (" + Fixed(1.0 / scan_period, 1) + " Hz)"
                                           : "scan period unknown (no time stamps)";
    timing += has_point_times ? ", per-point times" : ", no per-point times";
    timing += has_odometry_prior ? ", odometry prior" : "";
    lines.push_back(timing);
    if (!planar) {
        lines.push_back(ground_tilt_deg >= 0.0 ? "ground plane tilted " + Fixed(ground_tilt_deg, 1) + " deg in the sensor frame"
                                               : "no ground plane found in the first scans");
    }
    if (motion.scans > 0) lines.push_back(motion.Describe());
    return lines;
}

}  // namespace revisit
