#include "settings/scene_scale_watch.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/quantile.hpp"
#include "settings/auto_settings.hpp"

namespace revisit {
namespace {
/// Points sampled per sampled scan: ten scans give 99% quantiles from ~10k ranges.
constexpr std::size_t kSamplesPerScan = 1024;
}  // namespace

SceneScaleWatch::SceneScaleWatch(const PipelineConfig& config)
    : active_(config.input.auto_settings && config.input.follow_scene_scale &&
              config.explicit_keys.count("odometry.max_range") == 0),
      max_range_(config.odometry.max_range),
      // KISS-ICP's ratio (voxel = max_range / 100): beyond 100 voxels a scan's points are too sparse
      // for the map's resolution. The radish mit-killian log (0.1 m voxels) widened to 80 m kept 3 of
      // 12 verified closures.
      limit_(std::max(config.odometry.max_range, kVoxelsPerRange * config.odometry.VoxelSize())) {}

std::optional<SettingUpdate> SceneScaleWatch::Add(std::size_t position, const Scan& scan) {
    if (!active_) return std::nullopt;
    if (scans_++ % kSampleEvery == 0 && !scan.points.empty()) {
        const std::size_t stride = std::max<std::size_t>(1, scan.points.size() / kSamplesPerScan);
        for (std::size_t i = 0; i < scan.points.size(); i += stride) {
            const double range = scan.points[i].cast<double>().norm();
            if (range > 0.0 && std::isfinite(range)) ranges_.push_back(range);
        }
    }
    if (scans_ % kWindowScans != 0) return std::nullopt;
    if (ranges_.empty()) return std::nullopt;  // a window of empty scans says nothing about the scene
    const double p99 = Quantile(std::move(ranges_), 0.99);
    ranges_.clear();  // moved from: empty again for the next window
    const double wanted = std::min(MaxRangeFor(p99), limit_);
    if (wanted < kWidenFactor * max_range_) return std::nullopt;
    std::ostringstream reason;
    reason << "99% of the points of the last " << kWindowScans << " scans lie within " << std::round(p99 * 10.0) / 10.0
           << " m (x 1.5)";
    SettingUpdate update{position + 1, "odometry.max_range", max_range_, wanted, reason.str()};
    max_range_ = wanted;
    return update;
}

std::string DescribeUpdate(const SettingUpdate& update) {
    std::ostringstream out;
    out << "scan " << update.scan << ": " << update.key << " " << update.from << " -> " << update.to << " (" << update.reason << ")";
    return out.str();
}

}  // namespace revisit
