#pragma once
/// The scene's scale as a sequence unfolds (issue 14: settings "updated as the sequence unfolds where
/// that is safe"). A drive from a narrow street into open country, or a walk from a hall into a
/// courtyard, sees farther than its first scans did; a crop chosen from those scans would throw the
/// new structure away. Only the odometry's range crop follows, and only outwards: a wider or narrower crop changes which
/// points are registered, not the map's voxels, so it can change between two scans. The voxel sizes
/// and the closure detector's settings stay as chosen at the start (changing them would rebuild the
/// odometry's map and make local maps incomparable).
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "core/scan.hpp"
#include "config/config.hpp"
#include "runfolder/run_state.hpp"

namespace revisit {

class SceneScaleWatch {
  public:
    /// Scans per window; every `sample_every`-th scan of a window is sampled.
    static constexpr std::size_t kWindowScans = 50;
    static constexpr std::size_t kSampleEvery = 5;
    /// Widened when the rule asks for this much more. Never narrowed: a narrower crop would drop what
    /// the sensor has shown it sees (a 2D laser's corridor end, 50 m away, returns at the next turn,
    /// and the radish mit-killian log flapped 30 <-> 80 m with narrowing), and a wide crop costs only
    /// the rare far points.
    static constexpr double kWidenFactor = 1.5;
    /// ... up to this many map voxels (KISS-ICP: max_range = 100 voxels), or the starting range.
    static constexpr double kVoxelsPerRange = 100.0;

    /// Active when `config` derives its settings from the data (input.auto_settings,
    /// input.follow_scene_scale) and odometry.max_range was not given explicitly.
    explicit SceneScaleWatch(const PipelineConfig& config);
    bool active() const { return active_; }
    double max_range() const { return max_range_; }

    /// Looks at the raw (uncropped) scan at `position`; returns the change to apply from the next
    /// scan on, if the scene's scale calls for one. Deterministic; a few microseconds per scan.
    std::optional<SettingUpdate> Add(std::size_t position, const Scan& scan);

  private:
    bool active_ = false;
    double max_range_ = 0.0;
    double limit_ = 0.0;  ///< [m] widest crop the map's voxels support
    std::size_t scans_ = 0;
    std::vector<double> ranges_;     ///< sampled ranges of the current window [m]
};

/// "scan 1200: odometry.max_range 60 -> 110 (99% of the points ... )", for logs and summaries.
std::string DescribeUpdate(const SettingUpdate& update);

}  // namespace revisit
