#include "evaluation/ground_truth_closures.hpp"

#include "core/error.hpp"
#include "evaluation/voxel_set.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <limits>
#include <cstdint>
#include <utility>
#include <iomanip>
#include <istream>
#include <ostream>
#include <sstream>

namespace revisit {
namespace {

constexpr std::size_t kNoSegment = std::numeric_limits<std::size_t>::max();

void CheckConfig(const GtClosureConfig& config) {
    if (!(config.segment_length > 0.0)) throw ConfigError("ground truth: segment_length must be positive");
    if (!(config.voxel_size > 0.0)) throw ConfigError("ground truth: voxel_size must be positive");
    if (!(config.max_range > 0.0)) throw ConfigError("ground truth: max_range must be positive");
    if (config.voxel_subsample == 0) throw ConfigError("ground truth: voxel_subsample must be >= 1");
}

}  // namespace

bool SegmentCutter::Add(const Eigen::Vector3d& position) {
    // CumulativeDistance's sums, one scan at a time.
    if (last_position_) travel_ += (position - *last_position_).norm();
    last_position_ = position;
    const std::size_t scan = num_scans_++;
    const bool starts = segments_.empty() || travel_ - segments_.back().start_travel >= segment_length_;
    if (starts) segments_.push_back({scan, scan, travel_});
    segments_.back().last_scan = scan;
    return starts;
}

std::vector<GtSegment> CutSegments(const Poses& T_world_sensor, double segment_length) {
    SegmentCutter cutter(segment_length);
    for (const auto& T : T_world_sensor) cutter.Add(T.translation());
    return cutter.segments();
}

GroundTruthBuilder::GroundTruthBuilder(Poses T_world_sensor, const GtClosureConfig& config)
    : T_world_sensor_(std::move(T_world_sensor)), config_(config) {
    CheckConfig(config_);
    segments_ = CutSegments(T_world_sensor_, config_.segment_length);
    const std::size_t num_segments = segments_.size();
    segment_of_scan_.resize(T_world_sensor_.size());
    for (std::size_t s = 0; s < num_segments; ++s)
        for (std::size_t scan = segments_[s].first_scan; scan <= segments_[s].last_scan; ++scan) segment_of_scan_[scan] = s;
    // Segment origins in cells of max_range: a pair closer than that lies in neighbouring cells.
    for (std::size_t s = 0; s < num_segments; ++s) grid_[CellOf(s)].push_back(s);
    // Step 2 of METHOD.md section 7: candidates from the poses alone (cheap). They are not kept (a long
    // city drive has millions): only which segments take part, and the last later partner of each.
    needed_.assign(num_segments, 0);
    last_later_.assign(num_segments, kNoSegment);
    for (std::size_t j = 0; j < num_segments; ++j) {
        for (const std::size_t i : EarlierPartners(j)) {
            needed_[i] = needed_[j] = 1;
            last_later_[i] = j;  // j increases
        }
    }
    voxels_.resize(num_segments);
}

Eigen::Vector3i GroundTruthBuilder::CellOf(std::size_t segment) const {
    const Eigen::Vector3d origin = T_world_sensor_[segments_[segment].first_scan].translation();
    return (origin / config_.max_range).array().floor().cast<int>();
}

std::vector<std::size_t> GroundTruthBuilder::EarlierPartners(std::size_t j) const {
    const double min_gap = config_.min_travel > 0.0 ? config_.min_travel : config_.travel_gap_ranges * config_.max_range;
    const Eigen::Vector3d origin_j = T_world_sensor_[segments_[j].first_scan].translation();
    const Eigen::Vector3i cell = CellOf(j);
    std::vector<std::size_t> partners;
    for (int dx = -1; dx <= 1; ++dx) {
        for (int dy = -1; dy <= 1; ++dy) {
            for (int dz = -1; dz <= 1; ++dz) {
                const auto it = grid_.find(cell + Eigen::Vector3i(dx, dy, dz));
                if (it == grid_.end()) continue;
                for (const std::size_t i : it->second) {
                    if (i >= j) break;  // each cell lists its segments in order
                    if (segments_[j].start_travel - segments_[i].start_travel < min_gap) continue;
                    const Eigen::Vector3d origin_i = T_world_sensor_[segments_[i].first_scan].translation();
                    if ((origin_j - origin_i).norm() < config_.max_range) partners.push_back(i);
                }
            }
        }
    }
    std::sort(partners.begin(), partners.end());
    return partners;
}

void GroundTruthBuilder::LoadSetsFrom(std::function<PackedVoxels(std::size_t)> load, std::size_t budget_bytes) {
    load_ = std::move(load);
    budget_bytes_ = budget_bytes;
    resident_.assign(segments_.size(), 0);
    last_used_.assign(segments_.size(), 0);
}

std::size_t GroundTruthBuilder::MakeResident(std::size_t s, std::size_t batch) {
    last_used_[s] = batch;
    if (resident_[s]) return 0;
    voxels_[s] = load_(s);
    resident_[s] = 1;
    held_bytes_ += voxels_[s].bytes.size();
    return voxels_[s].bytes.size();
}

void GroundTruthBuilder::EvictToBudget() {
    if (held_bytes_ <= budget_bytes_) return;
    std::vector<std::pair<std::size_t, std::size_t>> by_use;  // (last batch, segment): oldest first
    for (std::size_t s = 0; s < resident_.size(); ++s)
        if (resident_[s]) by_use.emplace_back(last_used_[s], s);
    std::sort(by_use.begin(), by_use.end());
    for (const auto& [batch, s] : by_use) {
        if (held_bytes_ <= budget_bytes_) break;
        held_bytes_ -= voxels_[s].bytes.size();
        voxels_[s] = PackedVoxels{};
        resident_[s] = 0;
    }
}

void GroundTruthBuilder::BoundOverlapsWith(std::function<VoxelColumns(std::size_t)> columns) {
    columns_of_ = std::move(columns);
    columns_.assign(segments_.size(), std::nullopt);
}

bool GroundTruthBuilder::MayClose(std::size_t earlier, std::size_t later) {
    if (!columns_of_) return true;
    for (const std::size_t s : {earlier, later})
        if (!columns_[s]) columns_[s] = columns_of_(s);
    const VoxelColumns& a = *columns_[earlier];
    const VoxelColumns& b = *columns_[later];
    const std::size_t smaller = std::min(a.size, b.size);
    if (smaller == 0) return false;  // the overlap of an empty set is 0
    // The overlap is common / smaller, computed as this (monotone in common): at most the bound's.
    return static_cast<double>(CommonVoxelsAtMost(a, b)) / static_cast<double>(smaller) > config_.min_overlap;
}

void GroundTruthBuilder::Settle(std::size_t next_scan) {
    // Complete segments in batches: their pairs' overlaps in parallel, a bounded list at a time.
    constexpr std::size_t kBatchPairs = 1 << 16;
    while (settled_ < segments_.size() && segments_[settled_].last_scan < next_scan) {
        std::vector<GtSegmentPair> pairs;
        std::vector<std::size_t> measured;  // the pairs whose overlap is computed (the rest cannot close: 0)
        std::size_t end = settled_;
        const std::size_t batch = ++batches_;
        std::size_t batch_bytes = 0;  // loaded for this batch (LoadSetsFrom)
        while (end < segments_.size() && segments_[end].last_scan < next_scan && pairs.size() < kBatchPairs) {
            // With stored sets a batch also ends once its sets fill the budget: one batch's sets are in memory at once.
            if (load_ && end > settled_ && batch_bytes > budget_bytes_) break;
            for (const std::size_t i : EarlierPartners(end)) {
                if (MayClose(i, end)) {
                    if (load_) batch_bytes += MakeResident(end, batch) + MakeResident(i, batch);
                    measured.push_back(pairs.size());
                }
                pairs.push_back({i, end, 0.0});
            }
            ++end;
        }
        tbb::parallel_for(std::size_t{0}, measured.size(), [&](std::size_t k) {
            GtSegmentPair& pair = pairs[measured[k]];
            pair.overlap = OverlapCoefficientAbove(voxels_[pair.earlier], voxels_[pair.later], config_.min_overlap);
        });
        num_candidates_ += pairs.size();
        for (const auto& pair : pairs) {
            const bool closes = pair.overlap > config_.min_overlap;
            if (closes) closing_.push_back(pair);
            const double distance = (T_world_sensor_[segments_[pair.later].first_scan].translation() -
                                     T_world_sensor_[segments_[pair.earlier].first_scan].translation()).norm();
            const auto bin = static_cast<std::size_t>(distance / config_.segment_length);
            if (bin >= candidates_by_distance_.size()) {
                candidates_by_distance_.resize(bin + 1, 0);
                closing_by_distance_.resize(bin + 1, 0);
            }
            ++candidates_by_distance_[bin];
            closing_by_distance_[bin] += closes;
        }
        // A set is done with once its last pair is settled: as the earlier segment of its last later one,
        // or as a later segment that no segment after it pairs with.
        const auto drop = [this](std::size_t s) {
            if (load_ && resident_[s]) held_bytes_ -= voxels_[s].bytes.size(), resident_[s] = 0;
            voxels_[s] = PackedVoxels{};
            if (columns_of_) columns_[s].reset();
        };
        for (const auto& pair : pairs)
            if (last_later_[pair.earlier] == pair.later) drop(pair.earlier);
        for (std::size_t j = settled_; j < end; ++j)
            if (last_later_[j] == kNoSegment) drop(j);
        if (load_) EvictToBudget();
        settled_ = end;
        if (on_settled_) on_settled_(settled_);
    }
}

bool GroundTruthBuilder::NeedsScan(std::size_t index) const {
    return index < segment_of_scan_.size() && needed_[segment_of_scan_[index]];
}

void GroundTruthBuilder::AddScan(std::size_t index, const std::vector<Eigen::Vector3f>& points_in_sensor) {
    if (!NeedsScan(index)) return;
    AddVoxels(voxels_[segment_of_scan_[index]], T_world_sensor_[index], points_in_sensor, config_.voxel_size,
              config_.voxel_subsample);
}

std::size_t GroundTruthBuilder::HeldBytes() const {
    std::size_t bytes = 0;
    for (const auto& set : voxels_) bytes += set.bytes.capacity();
    return bytes;
}

GtClosures GroundTruthBuilder::Finish() {
    // Step 3: the overlap coefficient of every candidate pair not settled yet.
    Settle(std::numeric_limits<std::size_t>::max());
    GtClosures result;
    result.segments = segments_;
    result.num_candidate_pairs = num_candidates_;
    result.segment_pairs = closing_;
    result.distance_bin = config_.segment_length;
    result.candidates_by_distance = candidates_by_distance_;
    result.closing_by_distance = closing_by_distance_;
    std::sort(result.segment_pairs.begin(), result.segment_pairs.end(), [](const GtSegmentPair& a, const GtSegmentPair& b) {
        return std::make_pair(a.earlier, a.later) < std::make_pair(b.earlier, b.later);
    });
    // Step 4: every scan pair across the closing segment pairs.
    for (const auto& pair : result.segment_pairs) {
        const GtSegment& a = segments_[pair.earlier];
        const GtSegment& b = segments_[pair.later];
        for (std::size_t s = a.first_scan; s <= a.last_scan; ++s)
            for (std::size_t t = b.first_scan; t <= b.last_scan; ++t) result.scan_pairs.push_back(MakeScanPair(s, t));
    }
    std::sort(result.scan_pairs.begin(), result.scan_pairs.end());
    result.scan_pairs.erase(std::unique(result.scan_pairs.begin(), result.scan_pairs.end()), result.scan_pairs.end());
    return result;
}

double OverlapDistance(const GtClosures& closures) {
    // A threshold on distance predicts "closure" below it: each bin below adds its closing pairs as
    // right and its others as wrong. The best threshold maximises the running sum (a noisy far bin
    // cannot move it, as a first crossing of one half would).
    long long sum = 0, best = 0;
    std::size_t best_bins = 0;
    const std::size_t bins = std::min(closures.candidates_by_distance.size(), closures.closing_by_distance.size());
    for (std::size_t b = 0; b < bins; ++b) {
        const auto closing = static_cast<long long>(closures.closing_by_distance[b]);
        sum += 2 * closing - static_cast<long long>(closures.candidates_by_distance[b]);
        if (sum > best) {
            best = sum;
            best_bins = b + 1;
        }
    }
    return static_cast<double>(best_bins) * closures.distance_bin;
}

GtClosures ComputeGroundTruthClosures(const Poses& T_world_sensor, const ScanPointsFn& scan_points,
                                      const GtClosureConfig& config) {
    GroundTruthBuilder builder(T_world_sensor, config);
    const auto& segments = builder.segments();
    // One task per segment: AddScan is never concurrent within a segment.
    tbb::parallel_for(std::size_t{0}, segments.size(), [&](std::size_t s) {
        for (std::size_t scan = segments[s].first_scan; scan <= segments[s].last_scan; ++scan)
            if (builder.NeedsScan(scan)) builder.AddScan(scan, scan_points(scan));
    });
    return builder.Finish();
}

std::string GroundTruthCacheKey(const Poses& T_world_sensor, const GtClosureConfig& config, const std::string& salt) {
    std::uint64_t hash = 0xCBF29CE484222325ULL;  // FNV-1a, 64 bit
    const auto add_bytes = [&hash](const void* data, std::size_t size) {
        const auto* bytes = static_cast<const unsigned char*>(data);
        for (std::size_t k = 0; k < size; ++k) {
            hash ^= bytes[k];
            hash *= 0x100000001B3ULL;
        }
    };
    const std::uint64_t version = 2;  // bump when the algorithm's output changes
    add_bytes(&version, sizeof(version));
    const std::uint64_t count = T_world_sensor.size();
    add_bytes(&count, sizeof(count));
    for (const auto& T : T_world_sensor) add_bytes(T.matrix().data(), sizeof(double) * 16);
    const double values[] = {config.segment_length, config.voxel_size, config.min_overlap, config.max_range,
                             config.travel_gap_ranges, static_cast<double>(config.voxel_subsample), config.min_travel};
    add_bytes(values, sizeof(values));
    add_bytes(salt.data(), salt.size());
    std::ostringstream text;
    text << std::hex << std::setw(16) << std::setfill('0') << hash;
    return text.str();
}

void WriteGroundTruthClosures(std::ostream& out, const GtClosures& closures, const std::string& cache_key) {
    out << "revisit-gt-closures 2\nkey " << cache_key << "\ncandidates " << closures.num_candidate_pairs << '\n';
    out << std::setprecision(17);
    out << "segments " << closures.segments.size() << '\n';
    for (const auto& s : closures.segments) out << s.first_scan << ' ' << s.last_scan << ' ' << s.start_travel << '\n';
    out << "segment_pairs " << closures.segment_pairs.size() << '\n';
    for (const auto& p : closures.segment_pairs) out << p.earlier << ' ' << p.later << ' ' << p.overlap << '\n';
    out << "scan_pairs " << closures.scan_pairs.size() << '\n';
    for (const auto& p : closures.scan_pairs) out << p.first << ' ' << p.second << '\n';
    out << "distances " << closures.candidates_by_distance.size() << ' ' << closures.distance_bin << '\n';
    for (std::size_t b = 0; b < closures.candidates_by_distance.size(); ++b)
        out << closures.candidates_by_distance[b] << ' ' << closures.closing_by_distance[b] << '\n';
    out << "end\n";
}

std::optional<GtClosures> ReadGroundTruthClosures(std::istream& in, const std::string& expected_key) {
    // A corrupt count must not allocate more than the rest of the file can hold: every record is at
    // least two numbers and their separators (4 bytes).
    std::size_t bytes_left = std::numeric_limits<std::size_t>::max();
    if (const auto here = in.tellg(); here >= 0 && in.seekg(0, std::ios::end)) {
        bytes_left = static_cast<std::size_t>(in.tellg() - here);
        in.seekg(here);
    }
    const std::size_t kMaxCount = bytes_left / 4;
    std::string word, key;
    int version = 0;
    if (!(in >> word >> version) || word != "revisit-gt-closures" || version != 2) return std::nullopt;
    if (!(in >> word >> key) || word != "key" || key != expected_key) return std::nullopt;
    GtClosures closures;
    std::size_t count = 0;
    if (!(in >> word >> closures.num_candidate_pairs) || word != "candidates") return std::nullopt;
    if (!(in >> word >> count) || word != "segments" || count > kMaxCount) return std::nullopt;
    closures.segments.resize(count);
    for (auto& s : closures.segments)
        if (!(in >> s.first_scan >> s.last_scan >> s.start_travel)) return std::nullopt;
    if (!(in >> word >> count) || word != "segment_pairs" || count > kMaxCount) return std::nullopt;
    closures.segment_pairs.resize(count);
    for (auto& p : closures.segment_pairs)
        if (!(in >> p.earlier >> p.later >> p.overlap)) return std::nullopt;
    if (!(in >> word >> count) || word != "scan_pairs" || count > kMaxCount) return std::nullopt;
    closures.scan_pairs.resize(count);
    for (auto& p : closures.scan_pairs)
        if (!(in >> p.first >> p.second)) return std::nullopt;
    if (!(in >> word >> count >> closures.distance_bin) || word != "distances" || count > kMaxCount) return std::nullopt;
    closures.candidates_by_distance.resize(count);
    closures.closing_by_distance.resize(count);
    for (std::size_t b = 0; b < count; ++b)
        if (!(in >> closures.candidates_by_distance[b] >> closures.closing_by_distance[b])) return std::nullopt;
    if (!(in >> word) || word != "end") return std::nullopt;  // a truncated file is not a cache
    return closures;
}

}  // namespace revisit
