#pragma once
/// The odometry as stages of a TBB pipeline (issue 19). What a scan's registration does not owe to the
/// scans before it (PrepareScan: the range crop and, without deskewing, both downsamplings; half of a
/// KITTI scan's odometry) runs ahead for several scans at once, while the registrations follow one by
/// one in input order. At two threads the preparation of later scans then overlaps the registration
/// (README "Eighth round"). The poses are those of registering the scans in a loop, at any thread count.
#include <cstddef>
#include <functional>
#include <optional>
#include <vector>

#include "core/scan.hpp"
#include "odometry/lidar_odometry.hpp"
#include "odometry/preprocess.hpp"
#include "config/config.hpp"
#include "runfolder/run_state.hpp"
#include "settings/scene_scale_watch.hpp"

namespace revisit {

/// Scans in flight between reading and registration: with 4, the preparation of the next scans
/// waited for free tokens (2.03-2.10 ms per KITTI scan at two threads); with 6, 8 or 16 it ran ahead
/// (1.89-1.93 ms).
constexpr std::size_t kOdometryScansInFlight = 6;

/// A sequence whose first scan has fewer points runs as a plain loop: a 2D laser scan's preparation
/// (tens of microseconds) costs less than handing the scan to another thread (intel at two threads:
/// 0.061 ms per scan in stages, 0.049 in the loop).
constexpr std::size_t kStagedMinPoints = 10000;

class OdometryStages {
  public:
    /// A scan on its way through the stages.
    struct Item {
        std::size_t position = 0;              ///< among the scans admitted, from 0
        Scan scan;
        OdometryConfig settings;               ///< the crop and voxels it is prepared with
        PreparedScan prepared;
        std::optional<SettingUpdate> update;   ///< the scene scale's change, made after this scan
        double prepare_ms = 0.0;               ///< [ms] wall time of Prepare
    };

    /// The odometry with `config.odometry`; the range crop follows the scene's scale as
    /// SceneScaleWatch decides.
    explicit OdometryStages(const PipelineConfig& config);

    /// First stage, in input order: numbers the scan, picks its settings and asks the scene scale.
    void Admit(Item& item);
    /// Second stage, any order, several scans at once: PrepareScan.
    static void Prepare(Item& item);
    /// Third stage, in input order: the scan's pose (RegisterPrepared), then the scene scale's change.
    Eigen::Isometry3d Register(Item& item);

    LidarOdometry& odometry() { return odometry_; }

  private:
    LidarOdometry odometry_;
    SceneScaleWatch scene_scale_;
    OdometryConfig ahead_;   ///< the settings of the next scan admitted
    std::size_t admitted_ = 0;
};

/// The scans `next` gives (std::nullopt: no more) through the three stages on the TBB threads (a loop
/// below kStagedMinPoints), with `registered` called in input order with each item and its pose
/// (before the next registration).
void RunOdometryStages(OdometryStages& stages, const std::function<std::optional<Scan>()>& next,
                       const std::function<void(OdometryStages::Item&, const Eigen::Isometry3d&)>& registered);
/// The same over scans in memory (benchmarks, tests): each is moved through the stages and back into
/// `scans`, not copied.
void RunOdometryStages(OdometryStages& stages, std::vector<Scan>& scans,
                       const std::function<void(OdometryStages::Item&, const Eigen::Isometry3d&)>& registered);

}  // namespace revisit
