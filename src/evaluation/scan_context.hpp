#pragma once
/// The ScanContext baseline (Kim & Kim, IROS 2018), as its public C++ code (SCManager) computes it,
/// modified like the thesis' "ScanContext-10" to keep all candidates per query (METHOD.md section 8).
#include "evaluation/scan_pair.hpp"

#include <Eigen/Core>
#include <cstddef>
#include <functional>
#include <vector>

namespace revisit {

struct ScanContextConfig {
    int num_rings = 20;                ///< radial bins
    int num_sectors = 60;              ///< azimuthal bins (6 degrees each)
    double max_radius = 80.0;          ///< [m] points farther (in x, y) are ignored
    double sensor_height = 2.0;        ///< [m] added to z so bin values are heights above ground
    std::size_t exclude_recent = 50;   ///< the last 50 scans are never candidates
    std::size_t rebuild_period = 50;   ///< the ring-key search set is refreshed every 50 queries
    std::size_t num_candidates = 10;   ///< nearest ring keys verified per query
    double search_ratio = 0.1;         ///< fine shift search +-round(0.5 * ratio * sectors) = +-3 columns
    double distance_threshold = 0.13;  ///< accept below (the detector's default; the sweep ignores it)
};

struct ScanContextDescriptor {
    Eigen::MatrixXf bins;      ///< num_rings x num_sectors, maximum height per bin, 0 when empty
    Eigen::VectorXf ring_key;  ///< mean of each ring (row): rotation invariant
    Eigen::VectorXf sector_key;///< mean of each sector (column): for the coarse yaw shift
};

/// The descriptor of given bins: its ring and sector keys are their row and column means.
ScanContextDescriptor DescriptorOfBins(Eigen::MatrixXf bins);

/// Bin (ring, sector) of a point at radius r and azimuth theta in [0, 360) degrees:
/// ring = clamp(ceil(r / max_radius * rings), 1, rings) - 1, the same for sectors (SCManager's rule).
ScanContextDescriptor MakeScanContext(const std::vector<Eigen::Vector3f>& points_in_sensor,
                                      const ScanContextConfig& config);

struct ScanContextMatch {
    double distance = 1.0;  ///< 1 - mean cosine similarity of the columns non-empty in both [0..2]; 1 when none
    int shift = 0;          ///< columns the candidate is rotated by to fit the query
};

/// Distance minimized over column shifts: the coarse shift that best aligns the sector keys, then
/// +-search radius around it (SCManager::distanceBtnScanContext).
ScanContextMatch ScanContextDistance(const ScanContextDescriptor& query, const ScanContextDescriptor& candidate,
                                     const ScanContextConfig& config);

struct ScanContextCandidate {
    std::size_t query = 0;
    std::size_t candidate = 0;
    double distance = 1.0;
    int shift = 0;
};

/// Every candidate of every query over a sequence of descriptors, in query order. Scan q is queried
/// when q >= exclude_recent; its search set is scans [0, b + 1 - exclude_recent) where b is the scan
/// of the last rebuild (every rebuild_period queries), as SCManager's k-d tree. The search is an exact
/// k nearest neighbours over ring keys in k-d trees (RingKeyIndex; ties by lower index), parallel
/// over queries.
std::vector<ScanContextCandidate> SearchScanContext(const std::vector<ScanContextDescriptor>& descriptors,
                                                    const ScanContextConfig& config);
class ScanContextFile;
/// Called between runs of queries with how many of `total` scans are done (a minute at 100,000 scans).
using SearchProgress = std::function<void(std::size_t done, std::size_t total)>;
/// The same search over descriptors kept in a file (scan_context_file.hpp): the same candidates.
std::vector<ScanContextCandidate> SearchScanContext(const ScanContextFile& descriptors, const ScanContextConfig& config,
                                                    const SearchProgress& on_progress = {});

/// Candidates as scored scan pairs (score = distance: sweep with Acceptance::kScoreAtMost).
std::vector<ScoredPair> ScanContextPairs(const std::vector<ScanContextCandidate>& candidates);

}  // namespace revisit
