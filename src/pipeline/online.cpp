#include "pipeline/online.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <set>
#include <string>
#include <utility>

#include "core/voxel.hpp"
#include "optimization/map_overlap.hpp"
#include "optimization/trajectory_correction.hpp"
#include "pipeline/refinement_gate.hpp"
#include "pipeline/scan_trail.hpp"
#include "runfolder/map_points_file.hpp"
#include "runfolder/run_files.hpp"

namespace revisit {
namespace {

std::string FormatWeight(double weight) {
    char text[32];
    std::snprintf(text, sizeof(text), "%.2g", weight);
    return text;
}

/// The detector runs with a gate of 3 inliers so that the evaluation can sweep the acceptance
/// threshold from 3 (METHOD.md section 7); closures below the configured gamma are recorded but
/// never refined nor added to the graph.
constexpr int kSweepMinInliers = 3;

ClosureDetectorConfig SweepConfig(ClosureDetectorConfig config) {
    config.min_inliers = std::min(config.min_inliers, kSweepMinInliers);
    return config;
}

std::vector<Eigen::Vector3d> ToDouble(const std::vector<Eigen::Vector3f>& points) {
    std::vector<Eigen::Vector3d> out(points.size());
    for (std::size_t i = 0; i < points.size(); ++i) out[i] = points[i].cast<double>();
    return out;
}

std::vector<Eigen::Vector3f> Downsampled(const std::vector<Eigen::Vector3f>& points, double voxel) {
    const auto kept = VoxelDownsample(ToDouble(points), voxel);
    std::vector<Eigen::Vector3f> out(kept.size());
    for (std::size_t i = 0; i < kept.size(); ++i) out[i] = kept[i].cast<float>();
    return out;
}

/// Consecutive maps revisit when a scan of each lies within this share of a map's length of the other,
/// a map's length apart in travel (the pass back along a corridor, a metre or two beside the pass out;
/// the boundary the two maps share is less than a map's length apart). Only where maps carry nothing
/// over and register in the plane: 2D lasers (the 3D paths keep their consecutive-map rule).
constexpr double kConsecutiveRevisitShare = 0.1;

bool ConsecutiveRevisitsChecked(const PipelineConfig& config) { return config.odometry.planar && !config.local_map.carry_over; }

double MillisecondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

ClosurePipeline::ClosurePipeline(const PipelineConfig& config, std::unique_ptr<MapPointStore> store)
    : config_(config), store_(store ? std::move(store) : MakeMemoryMapStore()), mapper_(config.local_map),
      detector_(SweepConfig(config.detector)), refinement_gate_(config), free_space_(config),
      consistency_(config.consistency, OdometryNoise{config.graph_noise.odometry_translation_per_m,
                                                     config.graph_noise.odometry_rotation_per_m}) {
    if (config.output.elevation_ablation) {
        ClosureDetectorConfig elevation = SweepConfig(config.detector);
        elevation.density.elevation_instead = true;
        elevation.store_images = false;
        elevation_detector_.emplace(elevation);
    }
}

void ClosurePipeline::Time(const std::string& stage, double ms) {
    auto& timer = timings_[stage];
    timer.total_ms += ms;
    timer.count++;
}

PipelineUpdate ClosurePipeline::AddScan(std::size_t scan_index, const Eigen::Vector3f* points_in_sensor, std::size_t count,
                                        const Eigen::Isometry3d& T_world_sensor) {
    const auto start = std::chrono::steady_clock::now();
    free_space_.AddScan(scan_index, points_in_sensor, count, T_world_sensor);
    auto closed = mapper_.AddScan(scan_index, points_in_sensor, count, T_world_sensor);
    Time("local_map", MillisecondsSince(start));
    return closed ? ProcessMap(*closed) : PipelineUpdate{};
}

PipelineUpdate ClosurePipeline::Finish() {
    PipelineUpdate update;
    if (auto last = mapper_.Finish()) update = ProcessMap(*last);
    CheckAgainstOdometryOverlays();
    CalibrateDrift();
    Optimize(true);
    DropDownweighted();
    for (int round = 0; config_.proximity.enabled && round < config_.proximity.rounds; ++round) {
        if (AddProximityClosures() == 0) break;
        ApplyConsistency();
        Optimize(true);
        DropDownweighted();
    }
    return update;
}

PipelineUpdate ClosurePipeline::ProcessMap(const LocalMap& map) {
    PipelineUpdate update;
    auto start = std::chrono::steady_clock::now();
    // On the run folder's grid whatever the store: a map read back is the map the chain used, and the
    // Python pipeline (memory store) finds what `revisit run` finds.
    const auto stored = SnapToMapPointGrid(Downsampled(map.points, config_.output.map_voxel), MapPointStep(config_.output.map_voxel));
    store_->Put(map.id, stored);
    if (config_.proximity.enabled) footprints_.push_back(MapFootprint(stored, FootprintCell()));
    if (config_.proximity.enabled) trails_.push_back(MakeScanTrail(map.T_map_scan, map.travel_start));
    free_space_.CloseMap(map);
    Time("map_store", MillisecondsSince(start));

    start = std::chrono::steady_clock::now();
    const auto closures = detector_.AddMap(map);
    const auto& stats = detector_.last_stats();
    Time("detector", MillisecondsSince(start));
    Time("detector.ground", stats.ground_ms);
    Time("detector.density", stats.density_ms);
    Time("detector.features", stats.features_ms);
    Time("detector.tree", stats.tree_ms);
    Time("detector.ransac", stats.ransac_ms);
    const auto& comparisons = detector_.last_comparisons();
    comparisons_.insert(comparisons_.end(), comparisons.begin(), comparisons.end());
    const MapRecord& record = detector_.maps().back();
    if (on_map_closed) on_map_closed(map, record);

    MapRecordSummary summary;
    summary.id = map.id;
    summary.first_scan = map.first_scan;
    summary.last_scan = map.last_scan;
    summary.T_world_map = map.T_world_map;
    summary.T_world_map_corrected = map.T_world_map;
    summary.travel_start = map.travel_start;
    summary.travel_end = map.travel_end;
    summary.num_points = map.points.size();
    summary.num_keypoints = static_cast<int>(record.keypoints.size());
    summary.density_origin = record.origin;
    summary.density_resolution = record.resolution;
    summary.T_ground_map = record.T_ground_map;
    maps_.push_back(summary);
    nodes_.push_back(map.T_world_map);
    node_travel_.push_back(map.travel_start);
    AppendPositionIntegral(nodes_, node_travel_, node_position_integral_);
    corrected_nodes_.push_back(corrected_nodes_.empty() ? map.T_world_map
                                                        : corrected_nodes_.back() * nodes_[nodes_.size() - 2].inverse() *
                                                              map.T_world_map);
    std::optional<RefinementQuery> planes;  // the new map's, made once (NewMapPlanes)
    if (refinement_gate_.active() && map.id > 0 && nodes_.size() >= 2) {
        start = std::chrono::steady_clock::now();
        refinement_gate_.AddConsecutive(ToDouble(store_->Get(map.id - 1)), ToDouble(stored),
                                        nodes_.back().inverse() * nodes_[nodes_.size() - 2], map.first_scan,
                                        NewMapPlanes(stored, planes));
        Time("refinement.consecutive", MillisecondsSince(start));
    }

    const std::size_t first_new = closures_.size();
    const std::size_t verified_before = verified_edges_.size();
    for (const auto& closure : closures) closures_.push_back(VerifyClosure(closure, stored, planes));
    if (verified_edges_.size() > verified_before) ApplyConsistency();
    update.closures.assign(closures_.begin() + std::ptrdiff_t(first_new), closures_.end());
    if (elevation_detector_) {
        start = std::chrono::steady_clock::now();
        for (auto& closure : elevation_detector_->AddMap(map)) {
            ClosureRecord record_elevation;
            record_elevation.method = "elevation";
            record_elevation.closure = std::move(closure);
            record_elevation.reason = "ablation (not used for correction)";
            closures_.push_back(record_elevation);
            update.closures.push_back(std::move(record_elevation));
        }
        Time("detector.elevation_ablation", MillisecondsSince(start));
    }
    // The update carries both images' keypoints; the records kept for the whole run do not when the
    // detector's map records hold them (one session): a long run's tens of thousands of records would
    // each keep a copy of two maps' keypoints, the chain's growth per scan.
    for (std::size_t k = first_new; k < closures_.size(); ++k) {
        Closure& closure = closures_[k].closure;
        if (!KeypointsInDatabase(closure)) continue;
        std::vector<Eigen::Vector2f>().swap(closure.query_keypoints);
        std::vector<Eigen::Vector2f>().swap(closure.ref_keypoints);
    }
    // Each online update optimizes the whole graph: one after every closure adds up quadratically over a
    // long run (100,000 scans of a city: 441 updates of ~130 ms). Once the graph holds many closures an
    // update waits for a tenth as many new ones. The outputs come from the final optimization, which
    // starts from the odometry: they do not depend on when the updates ran.
    const int every = std::max(config_.graph_noise.optimize_every_closures, static_cast<int>(loop_edges_.size() / 10));
    if (accepted_since_optimization_ >= every) Optimize(false);
    update.closed_map = maps_.back();
    return update;
}

std::optional<SettingUpdate> ClosurePipeline::RmsGateUpdate() const { return refinement_gate_.Update(); }

double ClosurePipeline::FootprintCell() const {
    return std::max(config_.local_map.split_distance / 20.0, config_.output.map_voxel);
}

bool ClosurePipeline::RevisitsPredecessor(int query, const Poses& T_world_map) const {
    const auto q = std::size_t(query);
    if (!ConsecutiveRevisitsChecked(config_) || query < 1 || q >= trails_.size() || q >= T_world_map.size()) return false;
    const double length = config_.local_map.split_distance;
    return TrailRevisits(trails_[q - 1], T_world_map[q - 1], trails_[q], T_world_map[q], kConsecutiveRevisitShare * length, length);
}

bool ClosurePipeline::PathReturns(int query, int ref, const Poses& T_world_map) const {
    const auto q = std::size_t(query), r = std::size_t(ref);
    const auto& maps = detector_.maps();
    const double detour = config_.proximity.revisit_detour;
    if (detour <= 0.0 || q >= maps.size() || r >= maps.size() || q >= T_world_map.size() || r >= T_world_map.size()) return true;
    if (maps[q].session != maps[r].session) return true;  // another session: a revisit by definition
    // The platform went away and came back: the path is longer than the way between the two.
    const double travel = std::abs(maps[q].travel_start - maps[r].travel_start);
    const double straight = (T_world_map[q].translation() - T_world_map[r].translation()).norm();
    if (travel >= detour * straight) return true;
    // A path that came back to a corner of the earlier map (their starts far apart): its scans meet.
    const double length = config_.local_map.split_distance;
    return q < trails_.size() && TrailRevisits(trails_[r], T_world_map[r], trails_[q], T_world_map[q], kConsecutiveRevisitShare * length, length);
}

void ClosurePipeline::CheckAgainstOdometryOverlays() {
    const int below = config_.proximity.odometry_check_below;
    if (!config_.proximity.enabled || config_.proximity.rounds <= 0 || below <= 0 || !config_.consistency.enabled) return;
    std::size_t consistent = 0;
    for (const auto& record : closures_) consistent += record.accepted;
    // None: the pass below starts from the odometry anyway.
    if (consistent == 0 || consistent >= std::size_t(below)) return;
    // Few closures cannot check each other, and one that lays a corridor onto its twin agrees with
    // nothing but also contradicts nothing (measured: indoor-2d-360 with the prior-bias correction, a lone
    // closure 90 deg off the odometry over 240 m, within the drift bound). Where the odometry lays two
    // maps over each other and they register there (within one closure's error of it), the odometry is
    // right between them: that is evidence no closure gave. Such closures agree with the odometry by
    // construction, cannot land on a twin (one closure's error from the overlay), and may displace the
    // detector's in the maximum consistent set.
    if (AddProximityClosures(true) > 0) ApplyConsistency();
}

std::size_t ClosurePipeline::AddProximityClosures(bool from_odometry) {
    const auto start = std::chrono::steady_clock::now();
    // Pairs an accepted closure already joins, or this pass already registered, are not registered again;
    // except one whose registration moved the estimate too far (below): the next round starts from a
    // better estimate.
    std::set<std::pair<int, int>> done;
    for (std::size_t i = 0; i < closures_.size(); ++i) {
        const ClosureRecord& record = closures_[i];
        // A registration from the odometry's overlay failed from that estimate, not from the corrected one.
        const bool retry = record.method == "proximity" && !record.refinement.accepted &&
                           (record.refinement.reason.rfind(kCorrectionFromGuess, 0) == 0 || odometry_overlay_.count(i) != 0);
        if (record.accepted || (record.method == "proximity" && !retry)) done.insert({record.closure.query_id, record.closure.ref_id});
    }
    const auto& p = config_.proximity;
    // The pass confirms an estimate the closures already made right: a registration that has to move the
    // relative pose by more than one closure's error (PCM's closure sigma) shows the estimate is not right
    // there yet (drift no closure reached, or maps the odometry bent), and one started from it locks as
    // readily onto a wrong alignment (measured: every false one on the simulated walks and rooms moved it
    // 2-6 deg, the true ones on the real walk under 0.3 deg). The estimate's height is its own: no search.
    RefinementConfig confirm = refinement_gate_.Refinement();
    confirm.max_correction_translation = std::min(confirm.max_correction_translation, config_.consistency.closure_sigma_translation);
    confirm.max_correction_rotation =
        std::min(confirm.max_correction_rotation, config_.consistency.closure_sigma_rotation_deg * M_PI / 180.0);
    confirm.vertical_search = 0.0;
    // Consecutive maps are joined by the odometry and share their boundary (and the carried-over points):
    // not a revisit. But a 2D laser's maps (no carry-over) along a corridor walked there and back hold
    // both passes, and nothing else joins them: those pairs are registered (RevisitsPredecessor). Maps
    // further apart are registered when the path came back between them (PathReturns).
    const Poses& estimate = from_odometry ? nodes_ : corrected_nodes_;
    const auto pairs = PredictOverlaps(footprints_, estimate, FootprintCell(), p.min_overlap, p.max_per_map,
                                       [&](int query, int ref) {
                                           if (done.count({query, ref}) > 0) return true;
                                           if (query == ref + 1) return !RevisitsPredecessor(query, estimate);
                                           return !PathReturns(query, ref, estimate);
                                       });
    std::size_t verified = 0;
    const std::size_t first = closures_.size();
    std::vector<Eigen::Vector3f> query_points;  // pairs come grouped by query map: read and prepare each once
    std::optional<RefinementQuery> prepared;
    int query_loaded = -1;
    for (const auto& pair : pairs) {
        ClosureRecord record;
        record.method = "proximity";
        Closure& closure = record.closure;
        closure.query_id = pair.query;
        closure.ref_id = pair.ref;
        closure.query_scans = {maps_[std::size_t(pair.query)].first_scan, maps_[std::size_t(pair.query)].last_scan};
        closure.ref_scans = {maps_[std::size_t(pair.ref)].first_scan, maps_[std::size_t(pair.ref)].last_scan};
        closure.T_query_ref = (estimate[std::size_t(pair.query)].inverse() * estimate[std::size_t(pair.ref)]).matrix();
        const MapRecord& query_map = detector_.maps()[std::size_t(pair.query)];
        if (pair.query != query_loaded) {
            query_points = store_->Get(pair.query);
            query_loaded = pair.query;
            prepared.reset();
            if (!query_points.empty()) {
                prepared.emplace(ToDouble(query_points), confirm, UpInMap(query_map));
                prepared->KeepPlaneGrids();  // its next references reuse each gate's grid
            }
        }
        if (from_odometry) odometry_overlay_.insert(closures_.size());
        Refine(record, query_points, query_map, confirm, from_odometry, prepared ? &*prepared : nullptr);
        verified += record.refinement.accepted;
        closures_.push_back(std::move(record));
        if (on_proximity_progress) on_proximity_progress(closures_.size() - first, pairs.size());
    }
    Time("proximity", MillisecondsSince(start));
    return verified;
}

const RefinementQuery* ClosurePipeline::NewMapPlanes(const std::vector<Eigen::Vector3f>& stored,
                                                     std::optional<RefinementQuery>& planes) const {
    if (stored.empty()) return nullptr;
    // The planes depend only on the settings MadeWith checks, which the RMS gate's updates leave alone.
    if (!planes) planes.emplace(ToDouble(stored), refinement_gate_.Refinement(), UpInMap(detector_.maps().back()));
    return &*planes;
}

ClosureRecord ClosurePipeline::VerifyClosure(const Closure& closure, const std::vector<Eigen::Vector3f>& query_points,
                                             std::optional<RefinementQuery>& query_planes) {
    ClosureRecord record;
    record.closure = closure;
    if (closure.num_inliers < config_.detector.min_inliers) {
        record.reason = "below the acceptance threshold (" + std::to_string(closure.num_inliers) + " < " +
                        std::to_string(config_.detector.min_inliers) + " inliers)";
        return record;
    }
    // Closures are verified as their query map is added: it is the detector's newest map.
    Refine(record, query_points, detector_.maps().back(), refinement_gate_.Refinement(), true, NewMapPlanes(query_points, query_planes));
    return record;
}

void ClosurePipeline::Refine(ClosureRecord& record, const std::vector<Eigen::Vector3f>& query_points,
                             const MapRecord& query_map, const RefinementConfig& refinement, bool may_displace,
                             const RefinementQuery* prepared) {
    const Closure& closure = record.closure;
    const auto start = std::chrono::steady_clock::now();
    const auto ref_points = store_->Get(closure.ref_id);
    // A 2D pair below the overlap gate is judged by what both maps observed (free_space_gate.hpp).
    const RefinementConfig gates = free_space_.Registration(refinement, closure.query_id, closure.ref_id);
    // The query map's levelling gives the vertical along which the closure's height is searched.
    record.refinement = prepared ? RefineAlignment(ToDouble(ref_points), *prepared, Eigen::Isometry3d(closure.T_query_ref), gates)
                                 : RefineAlignment(ToDouble(ref_points), ToDouble(query_points),
                                                   Eigen::Isometry3d(closure.T_query_ref), gates, UpInMap(query_map));
    free_space_.Judge(record.refinement, refinement, closure.query_id, closure.ref_id);
    Time("refinement", MillisecondsSince(start));
    record.refined = true;
    record.accepted = record.refinement.accepted;
    record.reason = record.refinement.reason;
    if (record.accepted) {
        // The refinement measures T_query_ref (the reference origin seen from the query map), and its
        // information is expressed for that direction: the edge goes from the query node.
        PoseGraphEdge edge;
        edge.from = closure.query_id;
        edge.to = closure.ref_id;
        edge.T_from_to = record.refinement.T_query_ref;
        edge.is_loop = true;
        const auto& noise = config_.graph_noise;
        edge.information = noise.closure_information_from_registration && record.refinement.information.trace() > 0
                               ? record.refinement.information
                               : DiagonalInformation(noise.closure_sigma_translation, noise.closure_sigma_rotation);
        verified_edges_.push_back(edge);
        verified_closure_.push_back(closures_.size());
        consistency_.Add({closure.query_id, closure.ref_id, record.refinement.T_query_ref, double(closure.num_inliers)},
                         {&nodes_, &node_travel_, &node_position_integral_}, may_displace);
        ++accepted_since_optimization_;
    }
}

std::string ClosurePipeline::OdometryContradiction(const Closure& closure, std::size_t k) const {
    const double travel = std::abs(maps_[std::size_t(closure.query_id)].travel_start - maps_[std::size_t(closure.ref_id)].travel_start);
    char text[160];
    std::snprintf(text, sizeof(text), "contradicts the odometry (PCM: chi^2 %.1f > %.1f over %.0f m of travel)",
                  consistency_.OdometryChi2Of(k), config_.consistency.odometry_chi2_threshold, travel);
    return text;
}

void ClosurePipeline::DropDownweighted() {
    // The robust kernel has turned these nearly off; say so instead of calling them accepted, and
    // optimize again without them: nearly off is not off (a weight of 0.1 still pulled one simulated
    // corridor 10 m along), and the corrected trajectory, which the proximity pass starts from, must
    // follow only the accepted closures. Each round drops at least one edge, so this ends.
    while (true) {
        bool dropped = false;
        for (std::size_t i = 0; i < loop_edges_.size(); ++i) {
            ClosureRecord& record = closures_[loop_edge_closure_[i]];
            if (record.graph_weight >= config_.graph_noise.min_weight) continue;
            graph_rejected_.insert(loop_edge_closure_[i]);
            dropped = true;
        }
        if (!dropped) return;
        ApplyConsistency();
        Optimize(true);
    }
}

void ClosurePipeline::ApplyConsistency() {
    const auto start = std::chrono::steady_clock::now();
    const std::vector<char> keep = consistency_.ConsistentSet();
    loop_edges_.clear();
    loop_edge_closure_.clear();
    for (std::size_t k = 0; k < verified_edges_.size(); ++k) {
        ClosureRecord& record = closures_[verified_closure_[k]];
        record.accepted = keep[k] != 0 && graph_rejected_.count(verified_closure_[k]) == 0;
        if (graph_rejected_.count(verified_closure_[k]) != 0) {
            record.reason = "inconsistent with the pose graph (weight " + FormatWeight(record.graph_weight) + " < " +
                            FormatWeight(config_.graph_noise.min_weight) + ")";
            continue;
        }
        if (!record.accepted) {
            record.reason = consistency_.ContradictsOdometry(k) ? OdometryContradiction(record.closure, k)
                                                                 : "inconsistent with other closures (PCM)";
            record.graph_weight = 0.0;
            continue;
        }
        record.reason = record.refinement.reason;
        loop_edges_.push_back(verified_edges_[k]);
        loop_edge_closure_.push_back(verified_closure_[k]);
    }
    Time("consistency", MillisecondsSince(start));
}

void ClosurePipeline::CalibrateDrift() {
    // The configured rate is a prior for a sensor family (2D lasers: 2e-3 rad/m, auto_settings.cpp); the
    // closures the check kept measure this odometry's drift. A repetitive world's shifted twin (a room one
    // along) agrees with the true closures only under a loose rate, so the measured one decides.
    const auto& c = config_.consistency;
    if (!c.enabled || !c.calibrate_drift || config_.explicit_keys.count("graph.odometry_rotation_per_m") != 0) return;
    const ConsistencyOdometry odometry{&nodes_, &node_travel_, &node_position_integral_};
    const auto observed = consistency_.ObservedRotationRate(odometry, std::size_t(std::max(c.calibration_min_closures, 1)));
    if (!observed) return;
    const double configured = config_.graph_noise.odometry_rotation_per_m;
    const double calibrated = std::max(c.calibration_min_rotation_per_m, c.calibration_factor * *observed);
    if (calibrated >= configured) return;
    const auto start = std::chrono::steady_clock::now();
    OdometryNoise noise = consistency_.noise();
    noise.rotation_per_m = calibrated;
    consistency_ = consistency_.Rechecked(noise, odometry);
    config_.graph_noise.odometry_rotation_per_m = calibrated;
    Time("consistency", MillisecondsSince(start));
    ApplyConsistency();
    char reason[160];
    std::snprintf(reason, sizeof(reason), "drift calibration: the consistent closures show at most %.2g rad/m (x %.3g)",
                  *observed, c.calibration_factor);
    const std::size_t next_scan = maps_.empty() ? 0 : maps_.back().last_scan + 1;
    drift_calibration_ = SettingUpdate{next_scan, "graph.odometry_rotation_per_m", configured, calibrated, reason};
}

void ClosurePipeline::Optimize(bool final) {
    accepted_since_optimization_ = 0;
    if (nodes_.size() < 2 || loop_edges_.empty()) {
        corrected_nodes_ = nodes_;
        return;
    }
    const auto start = std::chrono::steady_clock::now();
    const auto& noise = config_.graph_noise;
    // Odometry uncertainty grows with the distance between map origins (OdometryInformation).
    std::vector<PoseGraphEdge> edges;
    OdometryNoise odometry_noise;
    odometry_noise.translation_per_m = noise.odometry_translation_per_m;
    odometry_noise.rotation_per_m = noise.odometry_rotation_per_m;
    for (std::size_t i = 1; i < nodes_.size(); ++i) {
        const Eigen::Isometry3d T_prev_next = nodes_[i - 1].inverse() * nodes_[i];
        const double travel = maps_[i].travel_start - maps_[i - 1].travel_start;
        edges.push_back({static_cast<int>(i - 1), static_cast<int>(i), T_prev_next, OdometryInformation(travel, odometry_noise), false});
    }
    const std::size_t num_odometry = edges.size();
    edges.insert(edges.end(), loop_edges_.begin(), loop_edges_.end());
    PoseGraphConfig graph = config_.graph;
    graph.max_time_s = final ? 0.0 : noise.online_time_budget;
    // Online, each update starts from the last one's estimate (the maps since chained on by their
    // odometry), not from the odometry, which made every update converge over the whole graph again
    // (11 -> 170 ms per update from 10,000 to 100,000 scans; from the last estimate 20% less). The
    // final optimization starts from the odometry: the outputs do not depend on the updates.
    const bool warm = !final && corrected_nodes_.size() == nodes_.size();
    const auto result = OptimizePoseGraph(warm ? corrected_nodes_ : nodes_, edges, graph);
    corrected_nodes_ = result.T_world_node;
    for (std::size_t i = 0; i < loop_edges_.size(); ++i) {
        closures_[loop_edge_closure_[i]].graph_weight = result.edge_weights[num_odometry + i];
    }
    for (std::size_t m = 0; m < maps_.size(); ++m) maps_[m].T_world_map_corrected = corrected_nodes_[m];
    Time(final ? "pose_graph.final" : "pose_graph.online", MillisecondsSince(start));
}

Poses ClosurePipeline::CorrectTrajectory(const Poses& T_world_sensor, const std::vector<int>& map_of_scan) const {
    return revisit::CorrectTrajectory(T_world_sensor, map_of_scan, nodes_, corrected_nodes_, {});
}

}  // namespace revisit
