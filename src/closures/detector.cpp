#include "closures/detector.hpp"

#include <algorithm>
#include <chrono>
#include <limits>
#include <numeric>
#include <opencv2/imgcodecs.hpp>
#include <string>
#include <tbb/parallel_for.h>

#include "closures/descriptor_matching.hpp"
#include "core/error.hpp"

namespace revisit {
namespace {

using Clock = std::chrono::steady_clock;
double MsSince(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

Eigen::Vector2d ToMetric(const MapRecord& record, const Eigen::Vector2f& pixel) {
    return record.origin + record.resolution * pixel.cast<double>();
}

}  // namespace

ClosureDetectorConfig ClosureDetectorConfig::Later() {
    ClosureDetectorConfig config;
    config.align_ground = true;
    config.features.harris_score = true;
    config.features.self_similar_distance = 35;
    config.selection = CandidateSelection::kAllAboveMin;
    config.min_matches = 3;
    config.min_inliers = 6;
    config.rematch = false;
    config.rank_by_nearest = false;
    config.ransac.sampling = RansacSampling::kRandom;
    config.ransac.max_trials = 688;  // ceil(log(0.001) / log(1 - 0.1^2))
    config.ransac.weighted_sampling = false;
    config.ransac.refit_inliers = true;
    return config;
}

ClosureDetectorConfig ClosureDetectorConfig::Robust(double skip_recent_travel_m) {
    ClosureDetectorConfig config;
    config.density.scaling = DensityScaling::kPercentile;
    config.features.min_keypoints = 150;
    config.features.pad_border = true;
    config.selection = CandidateSelection::kAllAboveMin;
    config.min_matches = 10;
    config.skip_recent_travel = skip_recent_travel_m;
    config.ransac.refit_inliers = true;
    return config;
}

MapFeatures ComputeMapFeatures(const LocalMap& map, const ClosureDetectorConfig& config, AddMapStats* stats) {
    MapFeatures result;
    auto start = Clock::now();
    std::vector<Eigen::Vector3f> levelled;
    const std::vector<Eigen::Vector3f>* points = &map.points;
    if (config.align_ground) {
        result.ground = AlignGround(map.points, config.ground);
        if (result.ground.aligned) {
            const Eigen::Isometry3f T = result.ground.T_ground_map.cast<float>();
            levelled.reserve(map.points.size());
            for (const auto& p : map.points) levelled.push_back(T * p);
            points = &levelled;
        }
    }
    if (stats) stats->ground_ms = MsSince(start);
    start = Clock::now();
    result.density = ComputeDensityImage(*points, config.density);
    if (stats) stats->density_ms = MsSince(start);
    start = Clock::now();
    result.features = ComputeFeatures(result.density.image, config.features);
    if (stats) stats->features_ms = MsSince(start);
    return result;
}

ClosureDetector::ClosureDetector(const ClosureDetectorConfig& config) : config_(config), tree_(config.tree) {}

std::vector<Closure> ClosureDetector::AddMap(const LocalMap& map) {
    AddMapStats stats;
    const auto start = Clock::now();
    auto features = ComputeMapFeatures(map, config_, &stats);
    auto closures = AddMap(map, std::move(features));
    stats.tree_ms = stats_.tree_ms;
    stats.ransac_ms = stats_.ransac_ms;
    stats.num_keypoints = stats_.num_keypoints;
    stats.num_candidates = stats_.num_candidates;
    stats.num_closures = stats_.num_closures;
    stats.total_ms = MsSince(start);
    stats_ = stats;
    return closures;
}

std::vector<Closure> ClosureDetector::AddMap(const LocalMap& map, MapFeatures features) {
    stats_ = AddMapStats{};
    for (const auto& record : records_) {
        if (record.session == session_ && record.id == map.id) {
            throw ConfigError("closures: map id " + std::to_string(map.id) + " added twice in session " +
                              std::to_string(session_));
        }
    }
    MapRecord record;
    record.id = map.id;
    record.session = session_;
    record.scans = {map.first_scan, map.last_scan};
    record.travel_start = map.travel_start;
    record.travel_end = map.travel_end;
    record.T_world_map = map.T_world_map;
    record.T_ground_map = features.ground.T_ground_map;
    record.origin = features.density.origin;
    record.resolution = features.density.resolution;
    record.rows = features.density.image.rows;
    record.cols = features.density.image.cols;
    record.keypoints = std::move(features.features.keypoints);
    if (config_.store_images) record.image_png = EncodeDensityPng(features.density.image);
    stats_.num_keypoints = int(record.keypoints.size());

    auto start = Clock::now();
    const auto& descriptors = features.features.descriptors;
    const auto matches = tree_.Match(descriptors);
    std::vector<int> votes(records_.size(), 0);
    for (const auto& m : matches) ++votes[m.map_id];
    // Each query descriptor matches the best descriptor of every map in its leaf, so every map of a
    // large database collects a similar floor of votes. The ranking counts, per query descriptor, only
    // the maps of its nearest match: evidence that concentrates on the map really seen again.
    std::vector<int> nearest_votes(records_.size(), 0);
    if (config_.rank_by_nearest) {
        for (std::size_t begin = 0; begin < matches.size();) {
            std::size_t end = begin;
            std::int32_t best = std::numeric_limits<std::int32_t>::max();
            for (; end < matches.size() && matches[end].query == matches[begin].query; ++end)
                best = std::min(best, matches[end].distance);
            for (std::size_t k = begin; k < end; ++k)
                if (matches[k].distance == best) ++nearest_votes[matches[k].map_id];
            begin = end;
        }
    }
    stats_.tree_ms = MsSince(start);

    start = Clock::now();
    std::vector<bool> skipped;
    const auto candidates = SelectCandidates(votes, nearest_votes, record, skipped);
    std::vector<int> slot(records_.size(), -1);
    for (std::size_t c = 0; c < candidates.size(); ++c) slot[candidates[c]] = int(c);
    std::vector<std::vector<TreeMatch>> grouped(candidates.size());
    for (const auto& m : matches) {
        if (slot[m.map_id] >= 0) grouped[slot[m.map_id]].push_back(m);
    }
    std::vector<Closure> verified(candidates.size());
    tbb::parallel_for(std::size_t(0), candidates.size(),
                      [&](std::size_t c) { verified[c] = Verify(record, descriptors, candidates[c], grouped[c]); });
    comparisons_.clear();
    std::vector<bool> is_candidate(records_.size(), false);
    for (std::size_t c : candidates) is_candidate[c] = true;
    for (std::size_t i = 0; i < records_.size(); ++i) {
        if (!skipped[i] && (votes[i] == 0 || is_candidate[i])) continue;
        comparisons_.push_back({record.id, records_[i].id, record.session, records_[i].session,
                                skipped[i] ? ComparisonStage::kSkippedRecent : ComparisonStage::kNotSelected, votes[i], 0});
    }
    for (std::size_t c = 0; c < candidates.size(); ++c) {
        const MapRecord& ref = records_[candidates[c]];
        comparisons_.push_back({record.id, ref.id, record.session, ref.session, ComparisonStage::kCompared,
                                votes[candidates[c]], verified[c].num_inliers});
    }
    std::vector<Closure> closures;
    for (auto& closure : verified) {
        if (closure.num_inliers >= config_.min_inliers) closures.push_back(std::move(closure));
    }
    std::stable_sort(closures.begin(), closures.end(),
                     [](const Closure& a, const Closure& b) { return a.num_inliers > b.num_inliers; });
    stats_.ransac_ms = MsSince(start);
    stats_.num_candidates = int(candidates.size());
    stats_.num_closures = int(closures.size());

    start = Clock::now();
    tree_.Add(descriptors, std::int32_t(records_.size()));
    stats_.tree_ms += MsSince(start);
    if (config_.rematch) record.descriptors = descriptors;
    records_.push_back(std::move(record));
    return closures;
}

const char* ComparisonStageName(ComparisonStage stage) {
    switch (stage) {
        case ComparisonStage::kSkippedRecent: return "skipped_recent";
        case ComparisonStage::kNotSelected: return "not_selected";
        case ComparisonStage::kCompared: return "compared";
    }
    return "compared";
}

ComparisonStage ComparisonStageFromName(const std::string& name) {
    for (auto stage : {ComparisonStage::kSkippedRecent, ComparisonStage::kNotSelected, ComparisonStage::kCompared}) {
        if (name == ComparisonStageName(stage)) return stage;
    }
    throw ConfigError("unknown comparison stage '" + name + "'");
}

std::vector<std::size_t> ClosureDetector::SelectCandidates(const std::vector<int>& votes, const std::vector<int>& nearest_votes,
                                                           const MapRecord& query,
                                                           std::vector<bool>& skipped) const {
    // METHOD.md section 4: never compare with the most recent maps of the same session.
    std::vector<std::size_t> same_session;
    for (std::size_t i = 0; i < records_.size(); ++i) {
        if (records_[i].session == query.session) same_session.push_back(i);
    }
    std::vector<bool> skip(records_.size(), false);
    if (config_.skip_recent_travel > 0.0) {
        for (std::size_t i : same_session) {
            skip[i] = query.travel_start - records_[i].travel_end < config_.skip_recent_travel;
        }
    } else {
        const std::size_t n = std::min<std::size_t>(same_session.size(), std::size_t(std::max(0, config_.skip_recent_maps)));
        for (std::size_t k = same_session.size() - n; k < same_session.size(); ++k) skip[same_session[k]] = true;
    }
    skipped = skip;
    std::vector<std::size_t> eligible;
    for (std::size_t i = 0; i < records_.size(); ++i) {
        if (!skip[i] && votes[i] > 0) eligible.push_back(i);
    }
    std::stable_sort(eligible.begin(), eligible.end(), [&](std::size_t a, std::size_t b) {
        if (config_.rank_by_nearest && nearest_votes[a] != nearest_votes[b]) return nearest_votes[a] > nearest_votes[b];
        return votes[a] > votes[b];
    });
    if (config_.selection == CandidateSelection::kTopHalf) {
        // Paper: the top N by votes, N = half the maps in the database (here never below min_candidates).
        const std::size_t half = std::max<std::size_t>(1, records_.size() / 2);
        eligible.resize(std::min(eligible.size(), std::max(half, std::size_t(std::max(1, config_.min_candidates)))));
    }
    std::vector<std::size_t> candidates;
    for (std::size_t i : eligible) {
        if (votes[i] >= config_.min_matches) candidates.push_back(i);
    }
    return candidates;
}

Closure ClosureDetector::Verify(const MapRecord& query, const std::vector<Descriptor>& query_descriptors,
                                std::size_t ref_index, const std::vector<TreeMatch>& matches) const {
    const MapRecord& ref = records_[ref_index];
    Closure closure;
    closure.query_id = query.id;
    closure.ref_id = ref.id;
    closure.query_session = query.session;
    closure.ref_session = ref.session;
    closure.query_scans = query.scans;
    closure.ref_scans = ref.scans;
    closure.num_votes = int(matches.size());
    closure.query_keypoints = query.keypoints;
    closure.ref_keypoints = ref.keypoints;
    if (config_.rematch && !ref.descriptors.empty()) {
        closure.matches = MatchMutualBest(query_descriptors, ref.descriptors, config_.tree.max_distance);
    } else {
        closure.matches.reserve(matches.size());
        for (const auto& m : matches) closure.matches.push_back({m.query, m.keypoint, m.distance});
    }
    std::vector<PointPair> pairs;
    pairs.reserve(closure.matches.size());
    for (const auto& m : closure.matches) {
        // Paper-era code weights samples by descriptor distance: closer descriptors are drawn more often.
        pairs.push_back({ToMetric(ref, ref.keypoints[m.ref_keypoint]), ToMetric(query, query.keypoints[m.query_keypoint]),
                         double(config_.tree.max_distance - m.distance)});
    }
    RansacConfig ransac = config_.ransac;
    ransac.inlier_distance = config_.inlier_pixels * std::max(query.resolution, ref.resolution);
    // One generator per pair of maps, seeded from the config: deterministic under any thread count.
    std::seed_seq seq{config_.ransac.seed, std::uint32_t(query.session), std::uint32_t(query.id),
                      std::uint32_t(ref.session), std::uint32_t(ref.id)};
    std::mt19937 rng(seq);
    const RansacResult result = AlignRansac2D(pairs, ransac, rng);
    closure.num_inliers = result.num_inliers;
    closure.inlier_mask = result.inliers;

    // METHOD.md section 5: T = T_ground_query^-1 * T_2d * T_ground_ref.
    Eigen::Isometry3d T_2d = Eigen::Isometry3d::Identity();
    T_2d.linear().topLeftCorner<2, 2>() = result.T_query_ref.linear();
    T_2d.translation().head<2>() = result.T_query_ref.translation();
    closure.T_query_ref = (query.T_ground_map.inverse() * T_2d * ref.T_ground_map).matrix();
    return closure;
}

cv::Mat ClosureDetector::Image(std::size_t index) const {
    const auto& png = records_.at(index).image_png;
    if (png.empty()) return {};
    return cv::imdecode(png, cv::IMREAD_GRAYSCALE);
}

std::vector<std::vector<Descriptor>> ClosureDetector::AllDescriptors() const {
    std::vector<std::vector<Descriptor>> result(records_.size());
    for (std::size_t i = 0; i < records_.size(); ++i) result[i].resize(records_[i].keypoints.size());
    for (const auto& entry : tree_.Entries()) result[entry.map_id][entry.keypoint] = entry.descriptor;
    return result;
}

std::size_t ClosureDetector::MemoryBytes() const {
    std::size_t bytes = tree_.MemoryBytes() + records_.capacity() * sizeof(MapRecord);
    for (const auto& r : records_) {
        bytes += r.keypoints.capacity() * sizeof(Eigen::Vector2f) + r.descriptors.capacity() * sizeof(Descriptor) +
                 r.image_png.capacity();
    }
    return bytes;
}

void ClosureDetector::Restore(MapRecord record, const std::vector<Descriptor>& descriptors) {
    if (descriptors.size() != record.keypoints.size()) {
        throw ConfigError("closures: restored map " + std::to_string(record.id) + " has " +
                          std::to_string(descriptors.size()) + " descriptors for " +
                          std::to_string(record.keypoints.size()) + " keypoints");
    }
    tree_.Add(descriptors, std::int32_t(records_.size()));
    if (config_.rematch) record.descriptors = descriptors;
    session_ = std::max(session_, record.session);
    records_.push_back(std::move(record));
}

std::vector<Closure> DetectClosures(const std::vector<LocalMap>& maps, const ClosureDetectorConfig& config) {
    ClosureDetector detector(config);
    std::vector<Closure> closures;
    for (const auto& map : maps) {
        auto found = detector.AddMap(map);
        closures.insert(closures.end(), std::make_move_iterator(found.begin()), std::make_move_iterator(found.end()));
    }
    return closures;
}

}  // namespace revisit
