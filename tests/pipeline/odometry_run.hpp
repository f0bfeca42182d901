#pragma once
/// The odometry over a whole dataset with the settings derived from the data (no preset, no --set),
/// as `revisit odometry DATASET` runs it, with the dataset's reference poses alongside.
#include <filesystem>

#include "core/trajectory.hpp"
#include "io/reader.hpp"
#include "odometry/lidar_odometry.hpp"
#include "settings/auto_settings.hpp"

namespace revisit::test {

struct OdometryRun {
    Poses estimate, reference;
    std::size_t fallbacks = 0;
};

inline OdometryRun RunOdometry(const std::filesystem::path& dataset) {
    PipelineConfig config;
    ConfigureFromData(config, dataset);
    auto reader = OpenDataset(dataset, MakeReaderOptions(config.input));
    LidarOdometry odometry(config.odometry);
    OdometryRun run;
    while (auto scan = reader->Next()) {
        run.estimate.push_back(odometry.RegisterScan(*scan));
        run.reference.push_back(scan->T_world_sensor.value_or(Eigen::Isometry3d::Identity()));
    }
    run.fallbacks = odometry.NumDegenerateFrames();
    return run;
}

}  // namespace revisit::test
