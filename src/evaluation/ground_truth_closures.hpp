#pragma once
/// Ground-truth loop closures from reference poses and scans by volumetric overlap
/// (METHOD.md section 7; thesis section 5.1, Eq. (5.1), the Szymkiewicz-Simpson overlap coefficient).
/// The protocol's scale (100 m range, 200 m of travel between the two) is a car's; the settings
/// from the data give walks and 2D lasers their own (settings/auto_settings.cpp).
#include "core/trajectory.hpp"
#include "evaluation/scan_pair.hpp"
#include "evaluation/voxel_set.hpp"

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <iosfwd>
#include <optional>
#include <unordered_map>
#include <string>
#include <vector>

namespace revisit {

struct GtClosureConfig {
    double segment_length = 2.0;     ///< [m] of travel per segment (key locations every 2 m)
    double voxel_size = 0.5;         ///< [m] voxel grid of each segment's accumulated scans
    double min_overlap = 0.5;        ///< a segment pair is a closure when overlap > this [0..1]
    double max_range = 100.0;        ///< [m] sensor range: segments whose first poses are farther apart are skipped
    double travel_gap_ranges = 2.0;  ///< later segment starts >= this * max_range of travel after the earlier one
    double min_travel = 0.0;         ///< [m] that travel itself when > 0 (replaces travel_gap_ranges * max_range)
    std::size_t voxel_subsample = 1; ///< keep 1 voxel in N, chosen by a hash of the voxel (the same voxels in
                                     ///< every segment, so the overlap stays an unbiased estimate); 1 = exact
};

/// A run of consecutive scans covering `segment_length` of travel.
struct GtSegment {
    std::size_t first_scan = 0;
    std::size_t last_scan = 0;  ///< inclusive
    double start_travel = 0.0;  ///< [m] travelled distance at the first scan
};

struct GtSegmentPair {
    std::size_t earlier = 0;  ///< segment index
    std::size_t later = 0;    ///< segment index
    double overlap = 0.0;     ///< |A n B| / min(|A|, |B|) of the two voxel sets
};

struct GtClosures {
    std::vector<GtSegment> segments;
    std::vector<GtSegmentPair> segment_pairs;  ///< closures only (overlap > min_overlap), sorted
    std::vector<ScanPair> scan_pairs;          ///< every scan pair across closing segments, sorted, unique
    std::size_t num_candidate_pairs = 0;       ///< segment pairs that passed the travel and distance limits
    /// The candidate pairs, and the closing ones among them, by the distance of their first poses in bins
    /// of `distance_bin` [m] (the segment length): how far apart this sensor's views of a place still
    /// overlap in this environment (OverlapDistance).
    double distance_bin = 0.0;
    std::vector<std::size_t> candidates_by_distance;
    std::vector<std::size_t> closing_by_distance;
};

/// The distance below which the ground truth's candidate pairs mostly overlap: the threshold on the
/// first poses' distance that best reproduces the overlap rule (the most closing minus non-closing
/// pairs below it, the nearest such threshold on ties) [m]. 0 when no distance does (no candidates,
/// or none of their distance bins closes more often than not).
double OverlapDistance(const GtClosures& closures);

/// Points of scan `index` in its sensor frame. Called concurrently from TBB workers: must be thread-safe.
using ScanPointsFn = std::function<std::vector<Eigen::Vector3f>(std::size_t index)>;

/// Segments of `segment_length` travel; a new one starts at the first scan at least that far from the
/// current segment's first scan (travel along the path). Stationary scans stay in the current segment.
std::vector<GtSegment> CutSegments(const Poses& T_world_sensor, double segment_length);

/// CutSegments one scan at a time, for a pass that sees the poses as the scans come (SegmentVoxelFile).
class SegmentCutter {
  public:
    explicit SegmentCutter(double segment_length) : segment_length_(segment_length) {}
    /// The next scan's position [m]; true when it starts a segment.
    bool Add(const Eigen::Vector3d& position);
    const std::vector<GtSegment>& segments() const { return segments_; }
    std::size_t num_scans() const { return num_scans_; }

  private:
    double segment_length_;
    std::vector<GtSegment> segments_;
    std::optional<Eigen::Vector3d> last_position_;
    double travel_ = 0.0;  ///< [m] as CumulativeDistance sums it
    std::size_t num_scans_ = 0;
};

/// The ground truth of a sequence; `T_world_sensor` holds one reference pose per scan. Segments are
/// voxelized in parallel (TBB), each by one task.
GtClosures ComputeGroundTruthClosures(const Poses& T_world_sensor, const ScanPointsFn& scan_points,
                                      const GtClosureConfig& config);

/// The same computation for scans that arrive one by one (a reader that streams, no random access):
/// the candidates come from the poses at construction, so only scans of segments that take part in a
/// candidate pair are needed, and only their voxel sets are kept, packed, until their last candidate
/// pair is settled.
class GroundTruthBuilder {
  public:
    GroundTruthBuilder(Poses T_world_sensor, const GtClosureConfig& config);
    /// False for scans whose segment is in no candidate pair: skip reading them.
    bool NeedsScan(std::size_t index) const;
    /// Adds a scan's points (sensor frame). Safe to call concurrently for scans of different segments.
    void AddScan(std::size_t index, const std::vector<Eigen::Vector3f>& points_in_sensor);
    /// The sets are stored (SegmentVoxelFile): `load(s)` gives segment s's set, and Settle loads each
    /// when a pair needs it and keeps at most about `budget_bytes` of them between batches (the least
    /// recently used are dropped and loaded again if a later pair needs them). A long drive's revisits
    /// would otherwise hold most sets until its end (~300 MB at 100,000 16-beam scans). Instead of
    /// AddScan; the result is the same.
    void LoadSetsFrom(std::function<PackedVoxels(std::size_t)> load, std::size_t budget_bytes);
    /// `columns(s)` gives segment s's VoxelColumns: a pair they prove cannot close is settled without
    /// its sets (with LoadSetsFrom, neither is loaded for it). Each is asked for once, when first
    /// needed, and kept until its segment's last pair. The result is the same.
    void BoundOverlapsWith(std::function<VoxelColumns(std::size_t)> columns);
    /// Called after each batch Settle completes, with the number of segments settled so far (progress).
    void OnSettled(std::function<void(std::size_t)> settled) { on_settled_ = std::move(settled); }
    /// For a caller that adds scans in order: every scan below `next_scan` has been added (or skipped).
    /// Computes the overlap of each candidate pair whose later segment is complete and frees every set
    /// no later pair needs, so a long sequence holds only the sets still waiting for a revisit. The
    /// result is the same as without it. Not concurrent with AddScan.
    void Settle(std::size_t next_scan);
    /// Overlaps of the candidate pairs not settled yet (parallel) and the closures. Scans never added
    /// count as empty. Settles everything: calling it again gives the same closures.
    GtClosures Finish();
    const std::vector<GtSegment>& segments() const { return segments_; }
    /// Bytes of the voxel sets held now.
    std::size_t HeldBytes() const;

  private:
    struct CellHash {
        std::size_t operator()(const Eigen::Vector3i& c) const {
            return std::size_t(c.x()) * 73856093u ^ std::size_t(c.y()) * 19349663u ^ std::size_t(c.z()) * 83492791u;
        }
    };
    Eigen::Vector3i CellOf(std::size_t segment) const;
    /// The candidates of segment j: earlier segments within max_range, at least the travel gap before it.
    std::vector<std::size_t> EarlierPartners(std::size_t j) const;
    /// LoadSetsFrom: segment s's set in memory, used by batch `batch`; returns the bytes it added.
    std::size_t MakeResident(std::size_t s, std::size_t batch);
    /// LoadSetsFrom: drops the least recently used sets until at most the budget is held.
    void EvictToBudget();
    /// False when the columns (BoundOverlapsWith) prove the pair's overlap is at most min_overlap.
    bool MayClose(std::size_t earlier, std::size_t later);

    Poses T_world_sensor_;
    GtClosureConfig config_;
    std::vector<GtSegment> segments_;
    std::vector<std::size_t> segment_of_scan_;
    std::unordered_map<Eigen::Vector3i, std::vector<std::size_t>, CellHash> grid_;  // segments by origin cell
    std::vector<char> needed_;               // per segment
    std::vector<std::size_t> last_later_;    // per segment: the last later segment it pairs with (or none)
    std::vector<PackedVoxels> voxels_;       // per segment
    std::function<VoxelColumns(std::size_t)> columns_of_;  // BoundOverlapsWith
    std::vector<std::optional<VoxelColumns>> columns_;    // per segment, while its pairs wait
    std::size_t settled_ = 0;                // segments [0, settled_) have every pair settled
    std::size_t num_candidates_ = 0;         // pairs settled
    std::vector<std::size_t> candidates_by_distance_, closing_by_distance_;  // settled pairs per segment_length
    std::vector<GtSegmentPair> closing_;     // settled pairs with overlap > min_overlap
    // LoadSetsFrom's cache
    std::function<PackedVoxels(std::size_t)> load_;
    std::function<void(std::size_t)> on_settled_;
    std::size_t budget_bytes_ = 0, held_bytes_ = 0, batches_ = 0;
    std::vector<char> resident_;             // per segment: its set is in voxels_
    std::vector<std::size_t> last_used_;     // per segment: the last batch that used it
};

/// 16 hex digits identifying the inputs: every pose bit, every config field and `salt` (e.g. the
/// dataset's path and scan count: the scans themselves are not hashed). Equal keys: reuse the cache.
std::string GroundTruthCacheKey(const Poses& T_world_sensor, const GtClosureConfig& config,
                                const std::string& salt = "");

/// Plain-text cache: a header with the key, then segments, segment pairs and scan pairs.
void WriteGroundTruthClosures(std::ostream& out, const GtClosures& closures, const std::string& cache_key);
/// The cached closures, or nullopt when the key differs or the text is not a complete cache (recompute).
std::optional<GtClosures> ReadGroundTruthClosures(std::istream& in, const std::string& expected_key);

}  // namespace revisit
