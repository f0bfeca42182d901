#include "runfolder/run_files.hpp"

#include <nlohmann/json.hpp>

#include <fstream>
#include <iomanip>
#include <limits>
#include <sstream>

#include "core/input_file.hpp"
#include "core/error.hpp"
#include "core/atomic_file.hpp"
#include "io/trajectory_io.hpp"
#include "optimization/trajectory_correction.hpp"
#include "runfolder/csv.hpp"
#include "runfolder/json_file.hpp"
#include "runfolder/run_manifest.hpp"

namespace revisit {
namespace fs = std::filesystem;
using nlohmann::json;

std::vector<int> MapOfScan(const std::vector<MapRecordSummary>& maps, std::size_t num_scans) {
    std::vector<std::size_t> first_scans;
    for (const auto& m : maps) first_scans.push_back(m.first_scan);
    return first_scans.empty() ? std::vector<int>(num_scans, -1) : NodeOfScan(first_scans, num_scans);
}

std::size_t RunState::NumAccepted() const {
    std::size_t n = 0;
    for (const auto& c : closures) n += CorrectsTrajectory(c) && c.accepted;
    return n;
}

namespace {

constexpr std::size_t kMaxMaps = 1'000'000'000;        ///< map ids are ints; larger is damage
constexpr double kMinDensityResolution = 0.005;        ///< [m/px] the config's lower bound for density resolutions

void WriteLines(const fs::path& file, const std::vector<std::string>& header, const std::vector<std::string>& rows) {
    WriteFileAtomically(file, [&](std::ostream& out) {
        for (std::size_t i = 0; i < header.size(); ++i) out << (i ? "," : "") << header[i];
        out << '\n';
        for (const auto& row : rows) out << row << '\n';
    });
}

std::vector<std::string> Concat(std::vector<std::string> a, const std::vector<std::string>& b) {
    a.insert(a.end(), b.begin(), b.end());
    return a;
}

void WriteJson(const fs::path& file, const json& value) {
    WriteJsonFile(file, value);
}

json ReadJson(const fs::path& file) {
    std::ifstream in = OpenForReading(file);
    try {
        return json::parse(in);
    } catch (const json::exception& e) {
        throw DatasetError(file, std::string("invalid JSON: ") + e.what());
    }
}

/// A non-negative integer field (0 when absent); any other number is damage, named.
std::size_t Count(const json& object, const char* key, const fs::path& file) {
    if (!object.contains(key)) return 0;
    const json& value = object.at(key);
    if (!value.is_number_unsigned()) throw DatasetError(file, std::string("'") + key + "' is not a count: " + value.dump());
    return value.get<std::size_t>();
}

fs::path ClosureDetailFile(const RunFolder& run, std::size_t index) {
    std::ostringstream name;
    name << std::setw(4) << std::setfill('0') << index << ".json";
    return run.root() / "closures" / name.str();
}

void WriteMaps(const RunFolder& run, const RunState& state) {
    const auto header = Concat(Concat(Concat({"id", "first_scan", "last_scan", "travel_start_m", "travel_end_m", "num_points",
                                              "num_keypoints", "density_origin_x", "density_origin_y", "density_resolution"},
                                             PoseColumns("T_world_map")),
                                      PoseColumns("T_world_map_corrected")),
                               PoseColumns("T_ground_map"));
    std::vector<std::string> rows;
    for (const auto& m : state.maps) {
        rows.push_back(CsvRow()
                           .Add(m.id).Add(m.first_scan).Add(m.last_scan).Add(m.travel_start).Add(m.travel_end)
                           .Add(m.num_points).Add(m.num_keypoints).Add(m.density_origin.x()).Add(m.density_origin.y())
                           .Add(m.density_resolution).AddPose(m.T_world_map).AddPose(m.T_world_map_corrected)
                           .AddPose(m.T_ground_map)
                           .Text());
    }
    WriteLines(run.local_maps_csv(), header, rows);
}

void WriteClosures(const RunFolder& run, const RunState& state) {
    const auto header = Concat(Concat(Concat({"index", "method", "query", "reference", "query_first_scan", "query_last_scan",
                                              "ref_first_scan", "ref_last_scan", "inliers", "votes"},
                                             PoseColumns("T_query_ref")),
                                      PoseColumns("T_query_ref_refined")),
                               {"overlap", "rms_m", "correspondences", "refined", "verified", "accepted", "graph_weight", "reason"});
    std::vector<std::string> rows;
    fs::create_directories(run.root() / "closures");
    for (std::size_t i = 0; i < state.closures.size(); ++i) {
        const auto& r = state.closures[i];
        const auto& c = r.closure;
        rows.push_back(CsvRow()
                           .Add(i).Add(r.method).Add(c.query_id).Add(c.ref_id).Add(c.query_scans.first)
                           .Add(c.query_scans.last).Add(c.ref_scans.first).Add(c.ref_scans.last).Add(c.num_inliers)
                           .Add(c.num_votes).AddPose(Eigen::Isometry3d(c.T_query_ref)).AddPose(r.refinement.T_query_ref)
                           .Add(r.refinement.overlap).Add(r.refinement.rms).Add(r.refinement.num_correspondences)
                           .Add(r.refined).Add(r.refinement.accepted).Add(r.accepted).Add(r.graph_weight).Add(r.reason)
                           .Text());
        // The density detector's keypoints within the run are its maps' in database.bin (a pair across
        // sessions keeps its own). The elevation ablation matched images of its own, which no page draws
        // (the pages show density images): its matches get no file (95% of the closure files before).
        if (r.method != "elevation") WriteClosureDetail(ClosureDetailFile(run, i), c, !KeypointsInDatabase(c));
    }
    WriteLines(run.closures_csv(), header, rows);
}

fs::path ComparisonsCsv(const RunFolder& run) { return run.root() / "comparisons.csv"; }

void WriteComparisons(const RunFolder& run, const RunState& state) {
    std::vector<std::string> rows;
    for (const auto& c : state.comparisons) {
        rows.push_back(CsvRow()
                           .Add(c.query_id).Add(c.ref_id).Add(c.query_session).Add(c.ref_session)
                           .Add(std::string(ComparisonStageName(c.stage))).Add(c.votes).Add(c.inliers)
                           .Text());
    }
    WriteLines(ComparisonsCsv(run), {"query", "reference", "query_session", "ref_session", "stage", "votes", "inliers"}, rows);
}

/// Runs written before comparisons were recorded have no comparisons.csv: nothing to read.
void ReadComparisons(const RunFolder& run, RunState& state) {
    const fs::path file = ComparisonsCsv(run);
    if (!fs::exists(file)) return;
    const auto table = CsvTable::Read(file);
    for (std::size_t i = 0; i < table.size(); ++i) {
        MapComparison c;
        c.query_id = static_cast<int>(table.Integer(i, "query"));
        c.ref_id = static_cast<int>(table.Integer(i, "reference"));
        c.query_session = static_cast<int>(table.Integer(i, "query_session"));
        c.ref_session = static_cast<int>(table.Integer(i, "ref_session"));
        try {
            c.stage = ComparisonStageFromName(table.Text(i, "stage"));
        } catch (const ConfigError& e) {
            throw DatasetError(file, e.what(), i + 2);
        }
        c.votes = static_cast<int>(table.Integer(i, "votes"));
        c.inliers = static_cast<int>(table.Integer(i, "inliers"));
        state.comparisons.push_back(c);
    }
}

Trajectory WithTimes(const RunState& state, const Poses& poses) {
    Trajectory t;
    t.poses = poses;
    t.timestamps = state.timestamps;
    return t;
}

json SettingUpdatesJson(const std::vector<SettingUpdate>& updates) {
    json out = json::array();
    for (const auto& u : updates) out.push_back({{"scan", u.scan}, {"key", u.key}, {"from", u.from}, {"to", u.to}, {"reason", u.reason}});
    return out;
}

/// The keypoint count local_maps.csv gives map `id` (a closure's match indices stay below it); 0 when the
/// run has no such map.
int KeypointsOfMap(const std::vector<MapRecordSummary>& maps, int id) {
    for (const auto& m : maps)
        if (m.id == id) return m.num_keypoints;
    return 0;
}

}  // namespace

void WriteClosureDetail(const fs::path& file, const Closure& c, bool with_keypoints) {
    // Without keypoints when they are database.bin's (the report reads them from there): they were ~95%
    // of every file (one file per candidate: 9 MB of a 6,600-scan highway's folder).
    json j;
    if (with_keypoints) {
        j["query_keypoints"] = json::array();
        for (const auto& k : c.query_keypoints) j["query_keypoints"].push_back({k.x(), k.y()});
        j["ref_keypoints"] = json::array();
        for (const auto& k : c.ref_keypoints) j["ref_keypoints"].push_back({k.x(), k.y()});
    }
    j["matches"] = json::array();
    for (std::size_t i = 0; i < c.matches.size(); ++i) {
        const auto& m = c.matches[i];
        j["matches"].push_back({m.query_keypoint, m.ref_keypoint, m.distance, i < c.inlier_mask.size() ? c.inlier_mask[i] : 0});
    }
    // One line: indented, every number took a line of its own and the file was 2.8x larger.
    WriteFileAtomically(file, JsonText(j, -1) + '\n');
}

void ReadClosureDetail(const fs::path& file, Closure& c, int num_query_keypoints, int num_ref_keypoints) {
    const json j = ReadJson(file);
    // Values are range-checked before conversion: a float cast out of range is undefined behaviour.
    const auto number = [&file](const json& value, double low, double high) {
        if (!value.is_number() || !(value.get<double>() >= low && value.get<double>() <= high)) {
            throw DatasetError(file, "malformed closure detail: value " + value.dump() + " outside [" +
                                         std::to_string(low) + ", " + std::to_string(high) + "]");
        }
        return value.get<double>();
    };
    constexpr double kMaxPixel = 1e6;  // keypoints are pixels of images at most density.max_image_side wide
    try {
        c.query_keypoints.clear();
        c.ref_keypoints.clear();
        c.matches.clear();
        c.inlier_mask.clear();
        // Run folders written before the keypoints moved out still carry them: read, and bound the matches by them.
        if (j.contains("query_keypoints") || j.contains("ref_keypoints")) {
            for (const auto& k : j.at("query_keypoints"))
                c.query_keypoints.emplace_back(number(k.at(0), -kMaxPixel, kMaxPixel), number(k.at(1), -kMaxPixel, kMaxPixel));
            for (const auto& k : j.at("ref_keypoints"))
                c.ref_keypoints.emplace_back(number(k.at(0), -kMaxPixel, kMaxPixel), number(k.at(1), -kMaxPixel, kMaxPixel));
            num_query_keypoints = static_cast<int>(c.query_keypoints.size());
            num_ref_keypoints = static_cast<int>(c.ref_keypoints.size());
        }
        for (const auto& m : j.at("matches")) {
            const auto query = static_cast<int>(number(m.at(0), 0, double(num_query_keypoints) - 1));
            const auto ref = static_cast<int>(number(m.at(1), 0, double(num_ref_keypoints) - 1));
            c.matches.push_back(FeatureMatch{query, ref, static_cast<int>(number(m.at(2), 0, 1024))});
            c.inlier_mask.push_back(static_cast<std::uint8_t>(number(m.at(3), 0, 1)));
        }
    } catch (const json::exception& e) {
        throw DatasetError(file, std::string("malformed closure detail: ") + e.what());
    }
}

void WriteRunState(const RunFolder& run, const RunState& state) {
    WriteKittiPoses(run.odometry_kitti(), state.odometry);
    WriteTumPoses(run.odometry_tum(), WithTimes(state, state.odometry));
    WriteKittiPoses(run.corrected_kitti(), state.corrected);
    WriteTumPoses(run.corrected_tum(), WithTimes(state, state.corrected));
    if (state.has_reference()) WriteTumPoses(run.reference_tum(), WithTimes(state, state.reference));
    if (state.has_partial_reference()) {
        Trajectory partial;
        partial.poses = state.reference;
        for (const std::size_t position : state.reference_scans) partial.timestamps.push_back(state.timestamps.at(position));
        WriteTumPoses(run.reference_tum(), partial);  // run.json's reference_scans says which scans these are
    }
    WriteMaps(run, state);
    WriteClosures(run, state);
    WriteComparisons(run, state);
    json timings = json::object();
    for (const auto& [stage, timer] : state.timings) {
        timings[stage] = {{"total_ms", timer.total_ms}, {"count", timer.count},
                          {"mean_ms", timer.count ? timer.total_ms / timer.count : 0.0}};
    }
    WriteJson(run.timings_json(), timings);
    WriteJson(run.run_info(), {{"dataset", state.dataset}, {"format", state.format}, {"poses", state.poses_source},
                               {"complete", state.complete}, {"truncated", !state.truncated.empty()},
                               {"truncated_reason", state.truncated}, {"scans", state.odometry.size()},
                               {"maps", state.maps.size()}, {"closures", state.closures.size()},
                               {"accepted_closures", state.NumAccepted()}, {"wall_seconds", state.wall_seconds},
                               {"peak_rss_kb", state.peak_rss_kb}, {"odometry_fallbacks", state.odometry_fallbacks},
                               {"reference_scans", state.reference_scans},
                               {"setting_updates", SettingUpdatesJson(state.setting_updates)},
                               {"revisit_version", "0.1.0"}, {"files", ManifestJson(ListRunFiles(run))}});
}

RunState ReadRunState(const RunFolder& run, bool closure_details) {
    RunState state;
    const json info = ReadJson(run.run_info());
    CheckRunManifest(run, info);  // before any file is trusted
    try {
        state.dataset = info.at("dataset").get<std::string>();
        state.format = info.at("format").get<std::string>();
        state.poses_source = info.at("poses").get<std::string>();
        state.complete = info.at("complete").get<bool>();
        state.truncated = info.value("truncated_reason", std::string());
        state.wall_seconds = info.value("wall_seconds", 0.0);
        state.peak_rss_kb = Count(info, "peak_rss_kb", run.run_info());
        state.odometry_fallbacks = info.value("odometry_fallbacks", std::vector<std::size_t>{});
        state.reference_scans = info.value("reference_scans", std::vector<std::size_t>{});
        for (const auto& u : info.value("setting_updates", json::array())) {
            state.setting_updates.push_back({u.at("scan").get<std::size_t>(), u.at("key").get<std::string>(), u.at("from").get<double>(),
                                             u.at("to").get<double>(), u.at("reason").get<std::string>()});
        }
    } catch (const json::exception& e) {
        throw DatasetError(run.run_info(), std::string("malformed run info: ") + e.what());
    }
    const Trajectory odometry = ReadTumPoses(run.odometry_tum());
    state.timestamps = odometry.timestamps;
    state.odometry = odometry.poses;
    state.corrected = ReadKittiPoses(run.corrected_kitti()).poses;
    if (fs::exists(run.reference_tum())) state.reference = ReadTumPoses(run.reference_tum()).poses;
    if (!state.reference_scans.empty()) {
        // A partial reference: one pose per listed scan, the scans in order and within the run.
        const auto& scans = state.reference_scans;
        if (scans.size() != state.reference.size()) {
            throw DatasetError(run.run_info(), "reference_scans lists " + std::to_string(scans.size()) + " scans, " +
                                                   run.reference_tum().string() + " has " + std::to_string(state.reference.size()) + " poses");
        }
        for (std::size_t k = 0; k < scans.size(); ++k) {
            if (scans[k] >= state.odometry.size() || (k > 0 && scans[k] <= scans[k - 1])) {
                throw DatasetError(run.run_info(), "reference_scans: entry " + std::to_string(k) + " (" + std::to_string(scans[k]) +
                                                       ") is not an increasing scan position below " + std::to_string(state.odometry.size()));
            }
        }
    }
    const auto maps = CsvTable::Read(run.local_maps_csv());
    for (std::size_t i = 0; i < maps.size(); ++i) {
        MapRecordSummary m;
        const std::size_t num_scans = state.odometry.size();
        m.id = static_cast<int>(maps.Index(i, "id", kMaxMaps));
        m.first_scan = maps.Index(i, "first_scan", num_scans);
        m.last_scan = maps.Index(i, "last_scan", num_scans);
        if (m.last_scan < m.first_scan) throw DatasetError(maps.file(), "last_scan is before first_scan", i + 2);
        m.travel_start = maps.Number(i, "travel_start_m");
        m.travel_end = maps.Number(i, "travel_end_m");
        m.num_points = maps.Index(i, "num_points", std::numeric_limits<std::size_t>::max());
        m.num_keypoints = static_cast<int>(maps.Index(i, "num_keypoints", std::numeric_limits<int>::max()));
        m.density_origin = {maps.Number(i, "density_origin_x"), maps.Number(i, "density_origin_y")};
        m.density_resolution = maps.Number(i, "density_resolution");
        // Every resolution the chain computes is >= density.min_resolution's lower bound: a smaller
        // one would ask for images of billions of pixels when drawn.
        if (m.density_resolution != 0.0 && !(m.density_resolution >= kMinDensityResolution)) {
            std::ostringstream problem;
            problem << "density_resolution " << m.density_resolution << " m/px is below the smallest a run writes ("
                    << kMinDensityResolution << " m/px)";
            throw DatasetError(maps.file(), problem.str(), i + 2);
        }
        m.T_world_map = maps.Pose(i, "T_world_map");
        m.T_world_map_corrected = maps.Pose(i, "T_world_map_corrected");
        m.T_ground_map = maps.Pose(i, "T_ground_map");
        state.maps.push_back(m);
    }
    state.map_of_scan = MapOfScan(state.maps, state.odometry.size());
    const auto closures = CsvTable::Read(run.closures_csv());
    for (std::size_t i = 0; i < closures.size(); ++i) {
        ClosureRecord r;
        r.method = closures.Text(i, "method");
        auto& c = r.closure;
        const std::size_t num_scans = state.odometry.size();
        constexpr auto kMaxCount = static_cast<std::size_t>(std::numeric_limits<int>::max());
        c.query_id = static_cast<int>(closures.Index(i, "query", kMaxMaps));
        c.ref_id = static_cast<int>(closures.Index(i, "reference", kMaxMaps));
        c.query_scans = {closures.Index(i, "query_first_scan", num_scans), closures.Index(i, "query_last_scan", num_scans)};
        c.ref_scans = {closures.Index(i, "ref_first_scan", num_scans), closures.Index(i, "ref_last_scan", num_scans)};
        c.num_inliers = static_cast<int>(closures.Index(i, "inliers", kMaxCount));
        c.num_votes = static_cast<int>(closures.Index(i, "votes", kMaxCount));
        c.T_query_ref = closures.Pose(i, "T_query_ref").matrix();
        r.refinement.T_query_ref = closures.Pose(i, "T_query_ref_refined");
        r.refinement.overlap = closures.Number(i, "overlap");
        r.refinement.rms = closures.Number(i, "rms_m");
        r.refinement.num_correspondences = static_cast<int>(closures.Index(i, "correspondences", kMaxCount));
        r.refined = closures.Integer(i, "refined") != 0;
        r.accepted = closures.Integer(i, "accepted") != 0;
        r.refinement.accepted = closures.Integer(i, "verified") != 0;
        r.graph_weight = closures.Number(i, "graph_weight");
        r.reason = closures.Text(i, "reason");
        r.refinement.reason = r.reason;
        const auto detail = ClosureDetailFile(run, i);
        if (closure_details && fs::exists(detail)) ReadClosureDetail(detail, c, KeypointsOfMap(state.maps, c.query_id), KeypointsOfMap(state.maps, c.ref_id));
        state.closures.push_back(std::move(r));
    }
    ReadComparisons(run, state);
    const json timings = ReadJson(run.timings_json());
    try {
        for (const auto& [stage, value] : timings.items()) {
            if (!value.is_object()) throw DatasetError(run.timings_json(), "stage '" + stage + "' is not an object");
            state.timings[stage] = StageTimer{value.value("total_ms", 0.0), Count(value, "count", run.timings_json())};
        }
    } catch (const json::exception& e) {
        throw DatasetError(run.timings_json(), std::string("malformed timings: ") + e.what());
    }
    return state;
}

}  // namespace revisit
