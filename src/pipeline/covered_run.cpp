#include "pipeline/covered_run.hpp"

#include <map>
#include <optional>

namespace revisit {

CoveredRun CoverOfReference(const RunState& run) {
    const std::size_t n = run.odometry.size();
    constexpr std::size_t kNone = static_cast<std::size_t>(-1);
    std::vector<std::size_t> reference_of_scan(n, kNone);  // index into run.reference
    for (std::size_t k = 0; k < run.reference_scans.size() && k < run.reference.size(); ++k)
        if (run.reference_scans[k] < n) reference_of_scan[run.reference_scans[k]] = k;

    CoveredRun covered;
    RunState& s = covered.state;
    s.dataset = run.dataset;
    s.format = run.format;
    s.poses_source = run.poses_source;
    s.complete = run.complete;
    s.truncated = run.truncated;
    std::vector<std::size_t> position_of_scan(n, kNone);  // in the covered run
    std::map<int, std::size_t> kept_maps;                 // id -> index in s.maps
    for (const auto& map : run.maps) {
        if (map.first_scan > map.last_scan || map.last_scan >= n) continue;
        bool whole = true;
        for (std::size_t scan = map.first_scan; scan <= map.last_scan && whole; ++scan) whole = reference_of_scan[scan] != kNone;
        if (!whole) continue;
        MapRecordSummary copy = map;
        copy.first_scan = covered.scans.size();
        for (std::size_t scan = map.first_scan; scan <= map.last_scan; ++scan) {
            position_of_scan[scan] = covered.scans.size();
            covered.scans.push_back(scan);
            s.timestamps.push_back(run.timestamps.at(scan));
            s.odometry.push_back(run.odometry.at(scan));
            s.corrected.push_back(run.corrected.at(scan));
            s.reference.push_back(run.reference.at(reference_of_scan[scan]));
        }
        copy.last_scan = covered.scans.size() - 1;
        kept_maps[map.id] = s.maps.size();
        s.maps.push_back(copy);
    }
    s.map_of_scan = MapOfScan(s.maps, s.odometry.size());

    // A closure is kept when both its maps are: its scan ranges are then those maps' scans.
    const auto covered_range = [&](int id, const ScanRange& range) -> std::optional<ScanRange> {
        const auto it = kept_maps.find(id);
        if (it == kept_maps.end() || range.last >= n || range.first > range.last) return std::nullopt;
        const std::size_t first = position_of_scan[range.first], last = position_of_scan[range.last];
        if (first == kNone || last == kNone || last - first != range.last - range.first) return std::nullopt;
        const auto& map = s.maps[it->second];
        if (first < map.first_scan || last > map.last_scan) return std::nullopt;
        return ScanRange{first, last};
    };
    for (const auto& record : run.closures) {
        const auto query = covered_range(record.closure.query_id, record.closure.query_scans);
        const auto ref = covered_range(record.closure.ref_id, record.closure.ref_scans);
        if (!query || !ref) {
            if (CorrectsTrajectory(record)) {
                ++covered.left_out_closures;
                covered.left_out_accepted += record.accepted;
            }
            continue;
        }
        ClosureRecord copy = record;
        copy.closure.query_scans = *query;
        copy.closure.ref_scans = *ref;
        s.closures.push_back(std::move(copy));
    }
    for (const auto& comparison : run.comparisons)
        if (kept_maps.count(comparison.query_id) && kept_maps.count(comparison.ref_id)) s.comparisons.push_back(comparison);
    for (const std::size_t scan : run.odometry_fallbacks)
        if (scan < n && position_of_scan[scan] != kNone) s.odometry_fallbacks.push_back(position_of_scan[scan]);
    return covered;
}

}  // namespace revisit
