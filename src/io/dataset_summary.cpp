#include "io/dataset_summary.hpp"

#include "core/printable.hpp"

#include <algorithm>
#include <iomanip>
#include <limits>

#include "core/trajectory.hpp"

namespace revisit {
namespace {

std::optional<DatasetSummary::Return> ClosestReturn(const Poses& poses, double min_travel) {
    const auto travel = CumulativeDistance(poses);
    std::optional<DatasetSummary::Return> best;
    std::size_t last_far = 0;  // poses [0, last_far) are more than min_travel behind pose i
    for (std::size_t i = 0; i < poses.size(); ++i) {
        while (last_far < i && travel[i] - travel[last_far] > min_travel) ++last_far;
        for (std::size_t j = 0; j < last_far; ++j) {
            const double d = (poses[i].translation() - poses[j].translation()).norm();
            if (!best || d < best->distance) best = DatasetSummary::Return{i, j, d, travel[i] - travel[j]};
        }
    }
    return best;
}

}  // namespace

DatasetSummary Summarize(Reader& reader, double revisit_min_travel, const std::function<void(std::size_t)>& progress) {
    DatasetSummary summary;
    std::vector<std::size_t> counts;
    Poses reference, odometry;
    while (auto scan = reader.Next()) {
        if (counts.empty()) summary.time_start = scan->timestamp;
        summary.time_end = scan->timestamp;
        counts.push_back(scan->points.size());
        summary.sensor_labels.insert(scan->sensor_label);
        if (scan->T_world_sensor) reference.push_back(*scan->T_world_sensor);
        if (scan->T_odom_sensor) odometry.push_back(*scan->T_odom_sensor);
        if (progress && counts.size() % 100 == 0) progress(counts.size());
    }
    summary.info = reader.Info();
    summary.stats = reader.Stats();
    summary.num_scans = counts.size();
    summary.scans_with_reference = reference.size();
    summary.scans_with_odometry = odometry.size();
    if (!counts.empty()) {
        std::sort(counts.begin(), counts.end());
        summary.points_min = counts.front();
        summary.points_max = counts.back();
        summary.points_median = counts[counts.size() / 2];
    }
    const bool use_reference = !reference.empty() && reference.size() >= odometry.size();
    const Poses& poses = use_reference ? reference : odometry;
    if (!poses.empty()) {
        summary.trajectory_source = use_reference ? "reference" : "odometry prior";
        summary.trajectory_length = PathLength(poses);
        summary.closest_return = ClosestReturn(poses, revisit_min_travel);
    }
    return summary;
}

void PrintSummary(std::ostream& out, const DatasetSummary& s) {
    out << std::fixed << std::setprecision(2);
    out << "dataset:          " << s.info.path.string() << '\n';
    out << "format:           " << s.info.format << '\n';
    out << "sensor labels:    ";
    for (const auto& label : s.sensor_labels) out << (label.empty() ? "(none)" : PrintableField(label)) << ' ';
    out << '\n';
    out << "scans:            " << s.num_scans << '\n';
    out << "points per scan:  min " << s.points_min << ", median " << s.points_median << ", max " << s.points_max << '\n';
    out << "time span:        " << (s.time_end - s.time_start) << " s";
    if (s.num_scans > 1) out << " (" << (s.num_scans - 1) / std::max(s.time_end - s.time_start, 1e-9) << " Hz)";
    if (!s.info.timing.empty()) out << "; " << s.info.timing;
    out << '\n';
    out << "reference poses:  " << (s.scans_with_reference > 0 ? "yes (" + std::to_string(s.scans_with_reference) + " scans)" : "no");
    if (!s.info.poses_file.empty()) out << " from " << s.info.poses_file.string();
    out << '\n';
    out << "odometry prior:   " << (s.scans_with_odometry > 0 ? "yes (" + std::to_string(s.scans_with_odometry) + " scans)" : "no") << '\n';
    if (s.trajectory_source.empty()) {
        out << "trajectory:       unknown (no poses in the dataset)\n";
    } else {
        out << "trajectory:       " << s.trajectory_length << " m (" << s.trajectory_source << ")\n";
        if (s.closest_return) {
            out << "closest return:   " << s.closest_return->distance << " m between scans " << s.closest_return->earlier_scan
                << " and " << s.closest_return->scan << " after " << s.closest_return->travel << " m of travel"
                << (s.closest_return->distance < 10.0 ? " (likely loops)" : " (probably no loop)") << '\n';
        } else {
            out << "closest return:   none (less than 50 m travelled)\n";
        }
    }
    const std::string drops = DescribeDrops(s.stats);
    if (!drops.empty()) out << "note:             " << drops << '\n';
}

}  // namespace revisit
