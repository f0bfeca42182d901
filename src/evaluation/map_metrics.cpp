#include "evaluation/map_metrics.hpp"

#include "core/error.hpp"
#include "evaluation/scan_pair.hpp"

#include <algorithm>
#include <cmath>

namespace revisit {
namespace {

/// Pairs (first, second) of `sorted` with first in [first_lo, first_hi] and second in [second_lo, second_hi]:
/// binary searches per first scan, so a closure costs its maps' length, not the ground truth's size.
std::size_t CountInRanges(const std::vector<ScanPair>& sorted, std::size_t first_lo, std::size_t first_hi,
                          std::size_t second_lo, std::size_t second_hi) {
    if (first_lo > first_hi || second_lo > second_hi) return 0;
    std::size_t count = 0;
    for (std::size_t first = first_lo; first <= first_hi; ++first) {
        const auto begin = std::lower_bound(sorted.begin(), sorted.end(), ScanPair{first, second_lo});
        const auto end = std::upper_bound(begin, sorted.end(), ScanPair{first, second_hi});
        count += static_cast<std::size_t>(end - begin);
    }
    return count;
}

/// Ground-truth pairs with one scan in each map, either way round (`sorted`: SortedUniquePairs).
std::size_t CountPairsBetween(const MapClosureForEval& c, const std::vector<ScanPair>& sorted) {
    const std::size_t forward = CountInRanges(sorted, c.ref_first_scan, c.ref_last_scan, c.query_first_scan, c.query_last_scan);
    const std::size_t backward = CountInRanges(sorted, c.query_first_scan, c.query_last_scan, c.ref_first_scan, c.ref_last_scan);
    // A pair with both scans where the two maps overlap is counted both ways: once is right.
    const std::size_t lo = std::max(c.ref_first_scan, c.query_first_scan), hi = std::min(c.ref_last_scan, c.query_last_scan);
    return forward + backward - CountInRanges(sorted, lo, hi, lo, hi);
}

}  // namespace

std::size_t MapIndexOfScan(const std::vector<MapRange>& maps, std::size_t scan) {
    const auto it = std::upper_bound(maps.begin(), maps.end(), scan,
                                     [](std::size_t s, const MapRange& m) { return s < m.first_scan; });
    if (it == maps.begin()) return maps.size();
    const std::size_t index = static_cast<std::size_t>(it - maps.begin()) - 1;
    return scan <= maps[index].last_scan ? index : maps.size();
}

MapRecall ComputeMapRecall(const std::vector<MapRange>& maps, const std::vector<MapClosureForEval>& closures,
                           const std::vector<ScanPair>& gt_scan_pairs, const MapMetricsConfig& config) {
    std::vector<char> revisits(maps.size(), 0), found(maps.size(), 0);
    std::vector<ScanPair> storage;
    const std::vector<ScanPair>& sorted = AsSortedUniquePairs(gt_scan_pairs, storage);
    for (const auto& pair : sorted) {
        const std::size_t a = MapIndexOfScan(maps, std::min(pair.first, pair.second));
        const std::size_t b = MapIndexOfScan(maps, std::max(pair.first, pair.second));
        if (a < maps.size() && b < maps.size() && a != b) revisits[std::max(a, b)] = 1;
    }
    for (const auto& closure : closures) {
        if (closure.inliers < config.min_inliers) continue;
        const std::size_t query = MapIndexOfScan(maps, closure.query_first_scan);
        if (query < maps.size() && CountPairsBetween(closure, sorted) > 0) found[query] = 1;
    }
    MapRecall recall;
    for (std::size_t m = 0; m < maps.size(); ++m) {
        recall.maps_with_revisit += revisits[m] ? 1 : 0;
        recall.maps_found_right += revisits[m] && found[m] ? 1 : 0;
    }
    if (recall.maps_with_revisit > 0) recall.recall = double(recall.maps_found_right) / double(recall.maps_with_revisit);
    return recall;
}

double YawOf(const Eigen::Isometry3d& T) {
    const Eigen::Vector3d x_axis = T.linear().col(0);
    return std::atan2(x_axis.y(), x_axis.x());
}

ClosurePoseError ClosureErrorAgainst(const Poses& T_world_sensor, std::size_t query_first_scan, std::size_t ref_first_scan,
                                     const Eigen::Isometry3d& T_query_ref) {
    if (query_first_scan >= T_world_sensor.size() || ref_first_scan >= T_world_sensor.size())
        throw ConfigError("map closure between scans " + std::to_string(query_first_scan) + " and " +
                          std::to_string(ref_first_scan) + " names a scan without a reference pose");
    const Eigen::Isometry3d T_gt_query_ref = T_world_sensor[query_first_scan].inverse() * T_world_sensor[ref_first_scan];
    const Eigen::Isometry3d error = T_gt_query_ref.inverse() * T_query_ref;
    return {error.translation().head<2>().norm(), std::abs(YawOf(error)) * 180.0 / M_PI};
}

MapMetrics EvaluateMapClosures(const std::vector<MapClosureForEval>& closures, const Poses& T_world_sensor,
                               const std::vector<ScanPair>& gt_scan_pairs, const MapMetricsConfig& config) {
    MapMetrics metrics;
    std::vector<double> translation_errors, yaw_errors;
    std::vector<ScanPair> storage;
    const std::vector<ScanPair>& sorted = AsSortedUniquePairs(gt_scan_pairs, storage);
    for (std::size_t k = 0; k < closures.size(); ++k) {
        const MapClosureForEval& c = closures[k];
        if (c.inliers < config.min_inliers) continue;
        MapClosureAssessment assessment;
        assessment.closure = k;
        assessment.gt_scan_pairs = CountPairsBetween(c, sorted);
        assessment.right_map = assessment.gt_scan_pairs > 0;
        const ClosurePoseError error = ClosureErrorAgainst(T_world_sensor, c.query_first_scan, c.ref_first_scan, c.T_query_ref);
        assessment.translation_error = error.translation;
        assessment.yaw_error_deg = error.yaw_deg;
        if (assessment.right_map) {
            ++metrics.num_right_maps;
            translation_errors.push_back(assessment.translation_error);
            yaw_errors.push_back(assessment.yaw_error_deg);
        }
        metrics.closures.push_back(assessment);
    }
    if (!metrics.closures.empty())
        metrics.fraction_right = double(metrics.num_right_maps) / double(metrics.closures.size());
    metrics.translation_error = ComputeStatistics(translation_errors);
    metrics.yaw_error_deg = ComputeStatistics(yaw_errors);
    return metrics;
}

}  // namespace revisit
