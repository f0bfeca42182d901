#pragma once
/// What `revisit info` reports about a dataset, computed in one streaming pass.
#include <functional>
#include <optional>
#include <ostream>
#include <set>

#include "io/reader.hpp"

namespace revisit {

struct DatasetSummary {
    DatasetInfo info;
    ReadStats stats;
    std::set<std::string> sensor_labels;
    std::size_t num_scans = 0;
    std::size_t points_min = 0, points_median = 0, points_max = 0;  ///< points per scan
    double time_start = 0.0, time_end = 0.0;                       ///< [s]
    std::size_t scans_with_reference = 0;
    std::size_t scans_with_odometry = 0;
    std::string trajectory_source;  ///< "reference", "odometry prior" or empty when there are no poses
    double trajectory_length = 0.0; ///< [m]
    /// Closest approach to an earlier place after travelling more than `revisit_min_travel`.
    struct Return {
        std::size_t scan = 0, earlier_scan = 0;
        double distance = 0.0;  ///< [m]
        double travel = 0.0;    ///< [m] travelled in between
    };
    std::optional<Return> closest_return;
};

/// Reads every scan once (one in memory at a time). `progress(scans_read)` is called every 100 scans.
DatasetSummary Summarize(Reader& reader, double revisit_min_travel = 50.0,
                         const std::function<void(std::size_t)>& progress = {});

/// Human-readable report, one fact per line.
void PrintSummary(std::ostream& out, const DatasetSummary& summary);

}  // namespace revisit
