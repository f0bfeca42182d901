#include "sessions/session_merge.hpp"

#include <algorithm>
#include <map>
#include <numeric>
#include <tuple>

#include "closures/database_io.hpp"
#include "core/error.hpp"
#include "evaluation/trajectory_metrics.hpp"
#include "optimization/trajectory_correction.hpp"
#include "runfolder/folder_map_store.hpp"
#include "runfolder/run_files.hpp"

namespace revisit {
namespace fs = std::filesystem;
namespace {

std::vector<Eigen::Vector3d> ToDouble(const std::vector<Eigen::Vector3f>& points) {
    std::vector<Eigen::Vector3d> out(points.size());
    for (std::size_t i = 0; i < points.size(); ++i) out[i] = points[i].cast<double>();
    return out;
}

/// Index into `maps` of every map id.
std::map<int, int> NodeOfMap(const std::vector<MapRecordSummary>& maps) {
    std::map<int, int> node;
    for (std::size_t i = 0; i < maps.size(); ++i) node[maps[i].id] = int(i);
    return node;
}

/// A stored map as the detector's input: the features it had when its run computed them.
std::pair<LocalMap, MapFeatures> StoredMap(const ClosureDetector& database, std::size_t index,
                                           const std::vector<Descriptor>& descriptors) {
    const MapRecord& record = database.maps()[index];
    LocalMap map;
    map.id = record.id;
    map.first_scan = record.scans.first;
    map.last_scan = record.scans.last;
    map.T_world_map = record.T_world_map;
    map.travel_start = record.travel_start;
    map.travel_end = record.travel_end;
    MapFeatures features;
    features.ground.T_ground_map = record.T_ground_map;
    features.ground.aligned = !record.T_ground_map.isApprox(Eigen::Isometry3d::Identity());
    features.density.image = database.Image(index);
    if (features.density.image.empty()) features.density.image = cv::Mat::zeros(record.rows, record.cols, CV_8UC1);
    features.density.origin = record.origin;
    features.density.resolution = record.resolution;
    features.features.keypoints = record.keypoints;
    features.features.descriptors = descriptors;
    return {std::move(map), std::move(features)};
}

Matrix6d ClosureInformation(const RefinementResult& refinement, const GraphNoiseConfig& noise) {
    return noise.closure_information_from_registration && refinement.information.trace() > 0
               ? refinement.information
               : DiagonalInformation(noise.closure_sigma_translation, noise.closure_sigma_rotation);
}

/// Cross-session candidates: each later session's maps query the database of every earlier session
/// (and their own, whose closures the run already has and are dropped here).
std::vector<CrossClosure> DetectCrossClosures(const std::vector<SessionRun>& sessions, const PipelineConfig& config) {
    ClosureDetector joint(config.detector);
    std::vector<CrossClosure> found;
    for (std::size_t s = 0; s < sessions.size(); ++s) {
        const RunFolder run(sessions[s].folder);
        const ClosureDetector database = LoadDatabase(run.database(), config.detector);
        const auto descriptors = database.AllDescriptors();
        while (joint.session() < int(s)) joint.StartSession();
        for (std::size_t i = 0; i < database.maps().size(); ++i) {
            if (s == 0) {
                MapRecord record = database.maps()[i];
                record.session = 0;
                joint.Restore(std::move(record), descriptors[i]);
                continue;
            }
            auto [map, features] = StoredMap(database, i, descriptors[i]);
            for (auto& closure : joint.AddMap(map, std::move(features))) {
                if (closure.query_session == closure.ref_session) continue;
                CrossClosure cross;
                cross.query_session = closure.query_session;
                cross.ref_session = closure.ref_session;
                cross.closure = std::move(closure);
                cross.up_in_query = UpInMap(joint.maps().back());
                found.push_back(std::move(cross));
            }
        }
    }
    return found;
}

/// 3D refinement of every candidate with the two runs' stored map points (read once per map).
void RefineCrossClosures(const std::vector<SessionRun>& sessions, const PipelineConfig& config, std::vector<CrossClosure>& cross) {
    std::map<std::pair<int, int>, std::vector<Eigen::Vector3d>> points;
    const auto points_of = [&](int session, int map_id) -> const std::vector<Eigen::Vector3d>& {
        auto it = points.find({session, map_id});
        if (it == points.end()) {
            const RunFolder run(sessions[std::size_t(session)].folder);
            it = points.emplace(std::make_pair(session, map_id), ToDouble(ReadMapPoints(run, map_id))).first;
        }
        return it->second;
    };
    for (auto& c : cross) {
        c.refinement = RefineAlignment(points_of(c.ref_session, c.closure.ref_id), points_of(c.query_session, c.closure.query_id),
                                       Eigen::Isometry3d(c.closure.T_query_ref), config.refinement, c.up_in_query);
        c.reason = c.refinement.accepted ? "" : c.refinement.reason;
    }
}

MultiSessionConfig GraphConfig(const PipelineConfig& config) {
    MultiSessionConfig graph;
    graph.graph = config.graph;
    graph.noise.translation_per_m = config.graph_noise.odometry_translation_per_m;
    graph.noise.rotation_per_m = config.graph_noise.odometry_rotation_per_m;
    graph.consistency = config.consistency;
    graph.min_cross_closures = config.fleet.min_cross_closures;
    graph.min_weight = config.graph_noise.min_weight;
    return graph;
}

/// APE of every session in the common frame; the common frame is tied to the reference frame by the
/// anchor session's alignment.
void ScoreSessions(MergeResult& result) {
    const std::size_t n = result.sessions.size();
    result.ape_common.assign(n, std::nullopt);
    result.ape_aligned.assign(n, std::nullopt);
    const RunState& anchor = result.sessions[0].state;
    if (!anchor.has_reference() || result.corrected[0].empty()) return;
    const Eigen::Isometry3d T_reference_common = AlignUmeyama(result.corrected[0], anchor.reference);
    for (std::size_t s = 0; s < n; ++s) {
        const RunState& state = result.sessions[s].state;
        if (!state.has_reference() || result.corrected[s].empty()) continue;
        Poses in_reference;
        for (const auto& T : result.corrected[s]) in_reference.push_back(T_reference_common * T);
        result.ape_common[s] = ComputeApe(in_reference, state.reference, false).errors.translation_stats.rmse;
        result.ape_aligned[s] = ComputeApe(result.corrected[s], state.reference, true).errors.translation_stats.rmse;
    }
}

}  // namespace

SessionRun LoadSessionRun(const fs::path& folder, bool allow_incomplete, std::ostream* log) {
    SessionRun session;
    session.folder = fs::absolute(folder).lexically_normal();
    const RunFolder run = RunFolder::Open(session.folder);
    session.options = ReadRunOptions(run);
    session.state = ReadRunState(run);
    if (!session.state.complete) {
        const std::string problem = "is an interrupted run (run.json: complete = false): it covers " +
                                    std::to_string(session.state.odometry.size()) + " scans, not its whole input";
        if (!allow_incomplete) throw DatasetError(folder, problem + "; finish it, or pass --allow-incomplete to merge it as it is");
        if (log) *log << "warning: " << folder.string() << ": " << problem << "; merged as it is (--allow-incomplete)\n";
    }
    if (!fs::exists(run.database())) throw DatasetError(run.database(), "missing: the run did not finish (no closure database)");
    if (session.state.maps.empty()) throw DatasetError(run.local_maps_csv(), "no local maps: nothing to merge");
    return session;
}

std::vector<SessionRun> LoadSessionRuns(const std::vector<fs::path>& folders, bool allow_incomplete, std::ostream* log) {
    std::vector<SessionRun> sessions;
    for (const auto& folder : folders) sessions.push_back(LoadSessionRun(folder, allow_incomplete, log));
    const auto key = [](const SessionRun& s) {
        return std::make_tuple(s.options.dataset.string(), s.options.from, s.options.to.value_or(SIZE_MAX), s.folder.string());
    };
    std::sort(sessions.begin(), sessions.end(), [&](const SessionRun& a, const SessionRun& b) { return key(a) < key(b); });
    for (std::size_t s = 1; s < sessions.size(); ++s) {
        if (fs::equivalent(sessions[s].folder, sessions[s - 1].folder))
            throw ConfigError("merge: run folder " + sessions[s].folder.string() + " is given twice");
    }
    return sessions;
}

PipelineConfig MergeConfig(const SessionRun& anchor, const std::vector<std::string>& overrides) {
    return LoadConfig({RunFolder(anchor.folder).config().string()}, overrides);
}

MergeResult MergeSessions(std::vector<SessionRun> sessions, const PipelineConfig& config, std::ostream& log) {
    MergeResult result;
    result.sessions = std::move(sessions);
    if (result.sessions.empty()) throw ConfigError("merge: no run folders");
    result.cross = DetectCrossClosures(result.sessions, config);
    RefineCrossClosures(result.sessions, config, result.cross);

    std::vector<SessionChain> chains;
    std::vector<SessionClosure> closures;
    std::vector<std::map<int, int>> node_of_map;
    for (std::size_t s = 0; s < result.sessions.size(); ++s) {
        const RunState& state = result.sessions[s].state;
        SessionChain chain;
        for (const auto& map : state.maps) {
            chain.T_odom_node.push_back(map.T_world_map);
            chain.travel.push_back(map.travel_start);
        }
        chains.push_back(std::move(chain));
        node_of_map.push_back(NodeOfMap(state.maps));
        for (const auto& record : state.closures) {
            if (!CorrectsTrajectory(record) || !record.accepted) continue;
            closures.push_back({int(s), node_of_map[s].at(record.closure.query_id), int(s), node_of_map[s].at(record.closure.ref_id),
                                record.refinement.T_query_ref, ClosureInformation(record.refinement, config.graph_noise),
                                double(record.closure.num_inliers)});
        }
    }
    const std::size_t num_in_session = closures.size();
    std::vector<std::size_t> cross_of_closure;
    for (std::size_t k = 0; k < result.cross.size(); ++k) {
        const auto& c = result.cross[k];
        if (!c.refinement.accepted) continue;
        closures.push_back({c.query_session, node_of_map[std::size_t(c.query_session)].at(c.closure.query_id), c.ref_session,
                            node_of_map[std::size_t(c.ref_session)].at(c.closure.ref_id), c.refinement.T_query_ref,
                            ClosureInformation(c.refinement, config.graph_noise), double(c.closure.num_inliers)});
        cross_of_closure.push_back(k);
    }
    result.graph = OptimizeSessions(chains, closures, GraphConfig(config));
    for (std::size_t i = 0; i < cross_of_closure.size(); ++i) {
        auto& c = result.cross[cross_of_closure[i]];
        c.accepted = result.graph.closure_accepted[num_in_session + i] != 0;
        c.reason = result.graph.closure_reason[num_in_session + i];
        c.graph_weight = result.graph.closure_weight[num_in_session + i];
    }

    result.corrected.assign(result.sessions.size(), {});
    for (std::size_t s = 0; s < result.sessions.size(); ++s) {
        if (!result.graph.connected[s]) {
            log << "warning: session " << s << " (" << result.sessions[s].folder.string()
                << ") has no cross-session closure tying it to the anchor: left out of the common frame\n";
            continue;
        }
        const RunState& state = result.sessions[s].state;
        result.corrected[s] = CorrectTrajectory(state.odometry, MapOfScan(state.maps, state.odometry.size()),
                                                chains[s].T_odom_node, result.graph.T_common_node[s]);
    }
    ScoreSessions(result);
    return result;
}

}  // namespace revisit
