#pragma once
/// Online closure detection: local maps in, closures out (METHOD.md sections 3-5).
#include <Eigen/Geometry>
#include <cstdint>
#include <string>
#include <vector>

#include "closures/closure.hpp"
#include "closures/density_image.hpp"
#include "closures/features.hpp"
#include "closures/ground_alignment.hpp"
#include "closures/hamming_tree.hpp"
#include "closures/local_map.hpp"
#include "closures/ransac2d.hpp"

namespace revisit {

enum class CandidateSelection {
    kTopHalf,     ///< paper: top N maps by votes, N = half the maps in the database, and >= min_matches
    kAllAboveMin, ///< later code: every map with at least min_matches matches
};

struct ClosureDetectorConfig {
    bool align_ground = false;  ///< later code: level each map on its ground plane before projecting
    GroundAlignmentConfig ground;
    DensityImageConfig density;
    FeatureConfig features;
    HammingTreeConfig tree;
    CandidateSelection selection = CandidateSelection::kTopHalf;
    /// Beyond the paper: the top half keeps at least this many maps. Half of a short drive's database is
    /// a handful of maps, and a revisit seen from another direction (a crossing) can rank just below it
    /// (the ScanContext baseline verifies 10 candidates). 1: the paper's rule.
    int min_candidates = 10;
    int min_matches = 25;          ///< paper: 25 (10 for small-FOV sensors); later code: 3 (more than 2)
    int skip_recent_maps = 3;      ///< never compare with the last maps of the same session
    /// Beyond the paper: when > 0, skip instead the maps of the same session whose travel ends less than
    /// this before the query's travel starts (METHOD.md 5b: counting maps fails on short sequences) [m].
    double skip_recent_travel = 0.0;
    RansacConfig ransac;           ///< inlier_distance is set per pair from inlier_pixels
    double inlier_pixels = 3.0;    ///< [pixels] RANSAC gate (1.5 m at 0.5 m per pixel)
    int min_inliers = 10;          ///< gamma: paper 10; later code 6 (more than 5)
    /// Beyond the paper: RANSAC on the mutual best matches between the query's and the candidate's
    /// descriptors instead of the tree's matches, which only see the one leaf each query descends to
    /// (the tree still votes and selects the candidates).
    bool rematch = true;
    /// Beyond the paper: the top-half rule ranks maps by the votes of query descriptors whose nearest
    /// match lies in them (ties and the min_matches gate: all votes).
    bool rank_by_nearest = true;
    bool store_images = true;      ///< keep the density images (PNG-compressed) for reports and persistence

    static ClosureDetectorConfig Paper() {
        ClosureDetectorConfig config;
        config.rematch = false;
        config.rank_by_nearest = false;
        config.min_candidates = 1;
        return config;
    }
    /// The authors' later public code (v2.x) where it differs from the paper.
    static ClosureDetectorConfig Later();
    /// Beyond the paper for small-scale / sparse sequences (METHOD.md 5b); keeps driving-scale behaviour.
    static ClosureDetectorConfig Robust(double skip_recent_travel_m);
};

/// What the detector keeps per stored map (descriptors live in the tree).
struct MapRecord {
    int id = 0;
    int session = 0;
    ScanRange scans;
    double travel_start = 0.0;  ///< [m]
    double travel_end = 0.0;    ///< [m]
    Eigen::Isometry3d T_world_map = Eigen::Isometry3d::Identity();
    Eigen::Isometry3d T_ground_map = Eigen::Isometry3d::Identity();
    Eigen::Vector2d origin = Eigen::Vector2d::Zero();  ///< density image origin [m]
    double resolution = 0.5;                           ///< [m per pixel]
    int rows = 0;
    int cols = 0;
    std::vector<Eigen::Vector2f> keypoints;  ///< [pixels]
    std::vector<Descriptor> descriptors;     ///< one per keypoint; kept only when rematch is on
    std::vector<std::uint8_t> image_png;     ///< empty unless store_images
};

/// The vertical in a map's own frame (its levelled ground's normal; +z when not levelled): the
/// direction along which the 3D refinement searches a closure's height.
inline Eigen::Vector3d UpInMap(const MapRecord& record) {
    return record.T_ground_map.linear().transpose() * Eigen::Vector3d::UnitZ();
}

/// Timings [ms] and counts of the last AddMap.
struct AddMapStats {
    double ground_ms = 0, density_ms = 0, features_ms = 0, tree_ms = 0, ransac_ms = 0, total_ms = 0;
    int num_keypoints = 0;
    int num_candidates = 0;
    int num_closures = 0;
};

/// What happened to one (query, earlier map) pair in AddMap, for "why was a revisit missed?". Pairs
/// that are not listed got no vote and were not skipped.
enum class ComparisonStage {
    kSkippedRecent,  ///< never compared: a recent map of the same session
    kNotSelected,    ///< voted for, but below min_matches (or outside the paper's top half)
    kCompared,       ///< RANSAC ran: `inliers` is its result (closures below the detector's gate are not returned)
};
struct MapComparison {
    int query_id = 0;
    int ref_id = 0;
    int query_session = 0;
    int ref_session = 0;
    ComparisonStage stage = ComparisonStage::kCompared;
    int votes = 0;
    int inliers = 0;
};
const char* ComparisonStageName(ComparisonStage stage);
/// Throws ConfigError on an unknown name.
ComparisonStage ComparisonStageFromName(const std::string& name);

/// The per-map front end without the database: levelling, density image, features.
struct MapFeatures {
    GroundAlignment ground;
    DensityImage density;
    Features features;
};
MapFeatures ComputeMapFeatures(const LocalMap& map, const ClosureDetectorConfig& config, AddMapStats* stats = nullptr);

class ClosureDetector {
  public:
    explicit ClosureDetector(const ClosureDetectorConfig& config = {});

    /// Queries the database with a newly closed map, adds it, and returns the closures it makes
    /// with earlier maps, best first. Throws ConfigError on a duplicate (session, id).
    std::vector<Closure> AddMap(const LocalMap& map);
    /// Same, for a map whose features were computed already (e.g. in parallel by the caller).
    std::vector<Closure> AddMap(const LocalMap& map, MapFeatures features);

    /// Later maps belong to a new session: the skip-recent rule does not apply across sessions.
    void StartSession() { ++session_; }
    int session() const { return session_; }

    const ClosureDetectorConfig& config() const { return config_; }
    const std::vector<MapRecord>& maps() const { return records_; }
    const HammingTree& tree() const { return tree_; }
    const AddMapStats& last_stats() const { return stats_; }
    /// Every skipped, voted-for or compared earlier map of the last AddMap.
    const std::vector<MapComparison>& last_comparisons() const { return comparisons_; }
    /// The stored density image of map `index` (into maps()); empty when images are not stored.
    cv::Mat Image(std::size_t index) const;
    /// Descriptors of every stored map, in keypoint order.
    std::vector<std::vector<Descriptor>> AllDescriptors() const;
    /// Heap bytes of the database (tree, records, images).
    std::size_t MemoryBytes() const;

    /// Restores one stored map (database loading); maps must come in their original order.
    void Restore(MapRecord record, const std::vector<Descriptor>& descriptors);

  private:
    /// `skipped` (out): per stored map, true when the skip-recent rule excluded it.
    std::vector<std::size_t> SelectCandidates(const std::vector<int>& votes, const std::vector<int>& nearest_votes,
                                              const MapRecord& query, std::vector<bool>& skipped) const;
    Closure Verify(const MapRecord& query, const std::vector<Descriptor>& query_descriptors, std::size_t ref_index,
                   const std::vector<TreeMatch>& matches) const;

    ClosureDetectorConfig config_;
    HammingTree tree_;
    std::vector<MapRecord> records_;
    int session_ = 0;
    AddMapStats stats_;
    std::vector<MapComparison> comparisons_;
};

/// Batch helper: every closure of a sequence of local maps, in order of detection.
std::vector<Closure> DetectClosures(const std::vector<LocalMap>& maps, const ClosureDetectorConfig& config = {});

}  // namespace revisit
