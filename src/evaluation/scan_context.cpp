#include "evaluation/scan_context.hpp"

#include "core/error.hpp"
#include "evaluation/azimuth_sector.hpp"
#include "evaluation/ring_key_index.hpp"
#include "evaluation/scan_context_file.hpp"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace revisit {
namespace {

/// Each column's squared norm, summed over the rows in order (the sums DirectDistance's per-column loop
/// would make: the same whatever the shift, so made once).
std::vector<double> ColumnSquaredNorms(const Eigen::MatrixXf& bins) {
    std::vector<double> norms(static_cast<std::size_t>(bins.cols()), 0.0);
    for (int c = 0; c < bins.cols(); ++c) {
        double sum = 0.0;
        for (int r = 0; r < bins.rows(); ++r) {
            const double v = bins(r, c);
            sum += v * v;
        }
        norms[static_cast<std::size_t>(c)] = sum;
    }
    return norms;
}

/// 1 - mean cosine similarity over columns that are non-empty in both (SCManager::distDirectSC), the
/// candidate's column c - shift (mod cols) against the query's column c (SCManager's circshift).
double DirectDistance(const Eigen::MatrixXf& query, const std::vector<double>& query_norms, const Eigen::MatrixXf& candidate,
                      const std::vector<double>& candidate_norms, int shift) {
    const int cols = static_cast<int>(query.cols()), rows = static_cast<int>(query.rows());
    double sum_similarity = 0.0;
    int num_columns = 0;
    for (int c = 0; c < cols; ++c) {
        const int source = c - shift < 0 ? c - shift + cols : c - shift;  // shift in [0, cols)
        const double norm_q = query_norms[static_cast<std::size_t>(c)], norm_c = candidate_norms[static_cast<std::size_t>(source)];
        if (norm_q == 0.0 || norm_c == 0.0) continue;
        const float* q = query.col(c).data();
        const float* v = candidate.col(source).data();
        double dot = 0.0;
        for (int r = 0; r < rows; ++r) dot += static_cast<double>(q[r]) * static_cast<double>(v[r]);
        sum_similarity += dot / std::sqrt(norm_q * norm_c);
        ++num_columns;
    }
    return num_columns == 0 ? 1.0 : 1.0 - sum_similarity / num_columns;
}

/// The shift of the candidate's sector key closest (L2) to the query's (SCManager::fastAlignUsingVkey).
int CoarseShift(const Eigen::VectorXf& query_key, const Eigen::VectorXf& candidate_key) {
    const int n = static_cast<int>(query_key.size());
    int best_shift = 0;
    double best = std::numeric_limits<double>::infinity();
    for (int shift = 0; shift < n; ++shift) {
        double squared = 0.0;
        for (int c = 0; c < n; ++c) {
            const double d = query_key(c) - candidate_key(c - shift < 0 ? c - shift + n : c - shift);
            squared += d * d;
        }
        if (squared < best) {
            best = squared;
            best_shift = shift;
        }
    }
    return best_shift;
}

void CheckConfig(const ScanContextConfig& config) {
    if (config.num_rings < 1 || config.num_sectors < 1) throw ConfigError("scan context: rings and sectors must be >= 1");
    if (!(config.max_radius > 0.0)) throw ConfigError("scan context: max_radius must be positive");
    if (config.rebuild_period == 0) throw ConfigError("scan context: rebuild_period must be >= 1");
}

}  // namespace

ScanContextDescriptor MakeScanContext(const std::vector<Eigen::Vector3f>& points_in_sensor,
                                      const ScanContextConfig& config) {
    CheckConfig(config);
    constexpr float kNoPoint = -1000.0f;  // SCManager's marker for empty bins, reset to 0 below
    Eigen::MatrixXf bins = Eigen::MatrixXf::Constant(config.num_rings, config.num_sectors, kNoPoint);
    // Single precision throughout, as SCManager (float points, float xy2theta).
    const float max_radius = static_cast<float>(config.max_radius);
    const float sensor_height = static_cast<float>(config.sensor_height);
    std::vector<int> sectors;  // ExactSector's bins, mostly without atan2
    const SectorOfAzimuth sector_of(config.num_sectors);
    sector_of(points_in_sensor, sectors);
    for (std::size_t k = 0; k < points_in_sensor.size(); ++k) {
        const Eigen::Vector3f& p = points_in_sensor[k];
        const float range = std::sqrt(p.x() * p.x() + p.y() * p.y());
        if (range > max_radius) continue;
        const int ring = ScanContextBin(range, max_radius, config.num_rings) - 1;
        const int sector = sectors[k];
        bins(ring, sector) = std::max(bins(ring, sector), p.z() + sensor_height);
    }
    return DescriptorOfBins((bins.array() == kNoPoint).select(0.0f, bins));
}

ScanContextDescriptor DescriptorOfBins(Eigen::MatrixXf bins) {
    ScanContextDescriptor descriptor;
    descriptor.ring_key = bins.rowwise().mean();
    descriptor.sector_key = bins.colwise().mean().transpose();
    descriptor.bins = std::move(bins);
    return descriptor;
}

ScanContextMatch ScanContextDistance(const ScanContextDescriptor& query, const ScanContextDescriptor& candidate,
                                     const ScanContextConfig& config) {
    const int cols = static_cast<int>(query.bins.cols());
    if (candidate.bins.rows() != query.bins.rows() || candidate.bins.cols() != cols)
        throw ConfigError("scan context: descriptors of different sizes");
    const int coarse = CoarseShift(query.sector_key, candidate.sector_key);
    const int radius = static_cast<int>(std::round(0.5 * config.search_ratio * cols));
    ScanContextMatch best;
    best.distance = std::numeric_limits<double>::infinity();
    const std::vector<double> query_norms = ColumnSquaredNorms(query.bins), candidate_norms = ColumnSquaredNorms(candidate.bins);
    for (int offset = -radius; offset <= radius; ++offset) {
        const int shift = ((coarse + offset) % cols + cols) % cols;
        const double distance = DirectDistance(query.bins, query_norms, candidate.bins, candidate_norms, shift);
        if (distance < best.distance) best = {distance, shift};
    }
    return best;
}

namespace {

/// The search over ring keys held in memory; `descriptor(scan)` gives a scan's whole descriptor (from
/// memory or from a file) for the candidates' distances.
template <class DescriptorOf>
std::vector<ScanContextCandidate> Search(const std::vector<Eigen::VectorXf>& ring_keys, const DescriptorOf& descriptor,
                                         const ScanContextConfig& config, const SearchProgress& on_progress = {}) {
    CheckConfig(config);
    const std::size_t n = ring_keys.size();
    const RingKeyIndex index(ring_keys, n);
    std::vector<std::vector<ScanContextCandidate>> per_query(n);
    const auto query = [&](std::size_t q) {
        // SCManager counts queries from the first that passes the size check and rebuilds every period.
        const std::size_t counter = q - config.exclude_recent;
        const std::size_t rebuilt_at = config.exclude_recent + (counter / config.rebuild_period) * config.rebuild_period;
        const std::size_t searchable = rebuilt_at + 1 - config.exclude_recent;
        const auto nearest = index.Nearest(ring_keys[q], searchable, config.num_candidates);
        if (nearest.empty()) return;
        const ScanContextDescriptor query = descriptor(q);  // a copy: `descriptor` may reuse its storage
        for (const auto& [squared, s] : nearest) {
            const ScanContextMatch match = ScanContextDistance(query, descriptor(s), config);
            per_query[q].push_back({q, s, match.distance, match.shift});
        }
    };
    // In runs of queries, so that the caller can show progress between them (each query's candidates
    // are its own: the same at any run length and thread count).
    constexpr std::size_t kRun = 4096;
    for (std::size_t begin = config.exclude_recent; begin < n; begin += kRun) {
        const std::size_t end = std::min(n, begin + kRun);
        tbb::parallel_for(begin, end, query);
        if (on_progress) on_progress(end, n);
    }
    std::vector<ScanContextCandidate> all;
    for (auto& candidates : per_query) all.insert(all.end(), candidates.begin(), candidates.end());
    return all;
}

}  // namespace

std::vector<ScanContextCandidate> SearchScanContext(const std::vector<ScanContextDescriptor>& descriptors,
                                                    const ScanContextConfig& config) {
    std::vector<Eigen::VectorXf> ring_keys(descriptors.size());
    for (std::size_t s = 0; s < descriptors.size(); ++s) ring_keys[s] = descriptors[s].ring_key;
    return Search(ring_keys, [&](std::size_t scan) -> const ScanContextDescriptor& { return descriptors[scan]; }, config);
}

std::vector<ScanContextCandidate> SearchScanContext(const ScanContextFile& descriptors, const ScanContextConfig& config,
                                                    const SearchProgress& on_progress) {
    // Neighbouring queries (one thread takes a run of them) verify mostly the same earlier scans: each
    // thread keeps the descriptors it read last instead of reading and decompressing them again.
    constexpr std::size_t kCachedPerThread = 256;
    struct Slot {
        std::size_t scan = std::numeric_limits<std::size_t>::max();
        ScanContextDescriptor descriptor;
    };
    tbb::enumerable_thread_specific<std::vector<Slot>> caches([] { return std::vector<Slot>(kCachedPerThread); });
    return Search(
        descriptors.ring_keys(),
        [&](std::size_t scan) -> const ScanContextDescriptor& {
            Slot& slot = caches.local()[scan % kCachedPerThread];
            if (slot.scan != scan) {
                slot.descriptor = descriptors.Get(scan);
                slot.scan = scan;
            }
            return slot.descriptor;
        },
        config, on_progress);
}

std::vector<ScoredPair> ScanContextPairs(const std::vector<ScanContextCandidate>& candidates) {
    std::vector<ScoredPair> pairs;
    pairs.reserve(candidates.size());
    for (const auto& c : candidates) pairs.push_back({MakeScanPair(c.query, c.candidate), c.distance});
    return pairs;
}

}  // namespace revisit
