/// The files of a merge (session_merge.hpp): sessions.json, cross_closures.csv, per-session
/// trajectories in the common frame and the joint map.
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <iomanip>

#include "core/atomic_file.hpp"
#include "core/owned_files.hpp"
#include "io/cloud_files.hpp"
#include "io/output_folder.hpp"
#include "io/trajectory_io.hpp"
#include "runfolder/json_file.hpp"
#include "optimization/global_map.hpp"
#include "runfolder/csv.hpp"
#include "runfolder/folder_map_store.hpp"
#include "sessions/merge_report.hpp"
#include "sessions/session_merge.hpp"
#include "report/svg_plot.hpp"

namespace revisit {
namespace fs = std::filesystem;
namespace {

std::string SessionFile(std::size_t session, const char* suffix) {
    char name[64];
    std::snprintf(name, sizeof(name), "session_%02zu_poses_%s.txt", session, suffix);
    return name;
}

/// A file name a merge writes (WriteMerge's names): an earlier merge's files of these names go
/// first, so a session that is no longer connected (or no longer there) leaves no trajectory behind.
bool IsMergeResultName(const std::string& name) {
    static const char* const kNames[] = {"sessions.json", "cross_closures.csv", "sessions.svg", "map_joint.ply", "index.html"};
    for (const char* n : kNames) {
        if (name == n) return true;
    }
    unsigned session = 0;
    if (std::sscanf(name.c_str(), "session_%u_", &session) != 1) return false;
    return name == SessionFile(session, "kitti") || name == SessionFile(session, "tum");
}

nlohmann::json Optional(const std::optional<double>& value) { return value ? nlohmann::json(*value) : nlohmann::json(nullptr); }

void WriteCrossClosures(const fs::path& file, const MergeResult& result) {
    std::string text;
    const auto header = [] {
        std::vector<std::string> columns = {"query_session", "query_map", "ref_session", "ref_map", "inliers", "votes"};
        for (const auto& c : PoseColumns("T_query_ref")) columns.push_back(c);
        for (const auto& c : PoseColumns("T_query_ref_refined")) columns.push_back(c);
        for (const char* c : {"overlap", "rms_m", "verified", "accepted", "graph_weight", "reason"}) columns.push_back(c);
        return columns;
    }();
    for (std::size_t i = 0; i < header.size(); ++i) text += (i ? "," : "") + header[i];
    text += '\n';
    for (const auto& c : result.cross) {
        text += CsvRow()
                    .Add(c.query_session).Add(c.closure.query_id).Add(c.ref_session).Add(c.closure.ref_id)
                    .Add(c.closure.num_inliers).Add(c.closure.num_votes).AddPose(Eigen::Isometry3d(c.closure.T_query_ref))
                    .AddPose(c.refinement.T_query_ref).Add(c.refinement.overlap).Add(c.refinement.rms)
                    .Add(c.refinement.accepted).Add(c.accepted).Add(c.graph_weight).Add(c.reason)
                    .Text() + '\n';
    }
    WriteFileAtomically(file, text);
}

/// Every connected session's trajectory in the common frame, one colour per session, and the accepted
/// cross-session closures as markers at the query map's origin; equal axes.
std::string SessionsSvg(const MergeResult& result) {
    LinePlotSpec spec;
    spec.title = "sessions in the common frame (markers: accepted cross-session closures)";
    spec.x_label = "x [m]";
    spec.y_label = "y [m]";
    spec.width = 720;
    spec.height = 640;
    double min_x = 1e300, max_x = -1e300, min_y = 1e300, max_y = -1e300;
    for (std::size_t s = 0; s < result.sessions.size(); ++s) {
        if (result.corrected[s].empty()) continue;
        PlotSeries series;
        series.name = "session " + std::to_string(s);
        series.color = SeriesColor(s);
        for (const auto& T : result.corrected[s]) {
            series.x.push_back(T.translation().x());
            series.y.push_back(T.translation().y());
            min_x = std::min(min_x, T.translation().x()), max_x = std::max(max_x, T.translation().x());
            min_y = std::min(min_y, T.translation().y()), max_y = std::max(max_y, T.translation().y());
        }
        spec.series.push_back(std::move(series));
    }
    if (spec.series.empty()) return LinePlotSvg(spec);
    for (const auto& c : result.cross) {
        if (!c.accepted) continue;
        const auto& maps = result.sessions[std::size_t(c.query_session)].state.maps;
        for (std::size_t m = 0; m < maps.size(); ++m) {
            if (maps[m].id != c.closure.query_id) continue;
            const Eigen::Vector3d p = result.graph.T_common_node[std::size_t(c.query_session)][m].translation();
            spec.markers.push_back({"", p.x(), p.y(), SeriesColor(std::size_t(c.ref_session))});
        }
    }
    // Equal metres per pixel on both axes (the plot area is about width - 80 by height - 80 pixels).
    const double span = std::max({max_x - min_x, (max_y - min_y) * 640.0 / 560.0, 1.0}) * 1.05;
    const double cx = 0.5 * (min_x + max_x), cy = 0.5 * (min_y + max_y);
    spec.x_range = std::make_pair(cx - span / 2, cx + span / 2);
    spec.y_range = std::make_pair(cy - span * 560.0 / 640.0 / 2, cy + span * 560.0 / 640.0 / 2);
    return LinePlotSvg(spec);
}

}  // namespace

void WriteMerge(const fs::path& out, bool force, MergeResult& result, const PipelineConfig& config) {
    PrepareOutputFolder(out, force);
    RemoveOwnFilesIf(out, IsMergeResultName);
    nlohmann::json sessions = nlohmann::json::array();
    GlobalMapBuilder joint_map(config.output.global_map_voxel, GlobalMapMaxPoints(config));
    std::size_t connected = 0;
    for (std::size_t s = 0; s < result.sessions.size(); ++s) {
        const SessionRun& session = result.sessions[s];
        const int in_session = int(session.state.NumAccepted());
        int cross = 0;
        for (const auto& c : result.cross) cross += c.accepted && (c.query_session == int(s) || c.ref_session == int(s));
        nlohmann::json entry = {{"session", s},
                                {"run", session.folder.string()},
                                {"dataset", session.options.dataset.string()},
                                {"from", session.options.from},
                                {"to", session.options.to ? nlohmann::json(*session.options.to) : nlohmann::json(nullptr)},
                                {"scans", session.state.odometry.size()},
                                {"maps", session.state.maps.size()},
                                {"connected", result.graph.connected[s] != 0},
                                {"in_session_closures", in_session},
                                {"cross_closures", cross},
                                {"ape_common_m", Optional(result.ape_common[s])},
                                {"ape_aligned_m", Optional(result.ape_aligned[s])}};
        if (result.graph.connected[s]) {
            ++connected;
            const RunFolder run(session.folder);
            WriteKittiPoses(out / SessionFile(s, "kitti"), result.corrected[s]);
            WriteTumPoses(out / SessionFile(s, "tum"), Trajectory{session.state.timestamps, result.corrected[s]});
            entry["poses_kitti"] = SessionFile(s, "kitti");
            entry["poses_tum"] = SessionFile(s, "tum");
            for (std::size_t m = 0; m < session.state.maps.size(); ++m)
                joint_map.Add(ReadMapPoints(run, session.state.maps[m].id), result.graph.T_common_node[s][m]);
        } else {
            entry["reason"] = "no verified cross-session closure ties it to the anchor (session 0): not placed in the common frame";
        }
        sessions.push_back(entry);
    }
    SavePly(out / "map_joint.ply", joint_map.Points());
    result.joint_map_points = joint_map.size();
    WriteCrossClosures(out / "cross_closures.csv", result);
    WriteFileAtomically(out / "sessions.svg", SessionsSvg(result));
    WriteMergeReport(out, result);

    int candidates = 0, verified = 0, accepted = 0;
    for (const auto& c : result.cross) {
        ++candidates;
        verified += c.refinement.accepted;
        accepted += c.accepted;
    }
    const nlohmann::json summary = {
        {"anchor", 0},
        {"common_frame", "odometry frame of session 0 (sessions are ordered by dataset, --from, --to, folder)"},
        {"sessions", sessions},
        {"connected_sessions", connected},
        {"cross_closures", {{"candidates", candidates}, {"verified", verified}, {"accepted", accepted}}},
        {"joint_map", "map_joint.ply"},
        {"joint_map_points", joint_map.size()},
        {"joint_map_voxel", joint_map.voxel_size()},
        {"graph_iterations", result.graph.iterations}};
    WriteJsonFile(out / "sessions.json", summary);
}

void PrintMergeSummary(std::ostream& out, const MergeResult& result, const fs::path& folder) {
    out << "session  connected  maps  closures(in/cross)  APE common [m]  run\n";
    for (std::size_t s = 0; s < result.sessions.size(); ++s) {
        const auto& session = result.sessions[s];
        const int in_session = int(session.state.NumAccepted());
        int cross = 0;
        for (const auto& c : result.cross) cross += c.accepted && (c.query_session == int(s) || c.ref_session == int(s));
        char line[160];
        std::snprintf(line, sizeof(line), "%7zu  %9s  %4zu  %8d / %-7d  %14s  ", s, result.graph.connected[s] ? "yes" : "NO",
                      session.state.maps.size(), in_session, cross,
                      result.ape_common[s] ? std::to_string(*result.ape_common[s]).substr(0, 6).c_str() : "-");
        out << line << session.folder.string() << '\n';
    }
    int verified = 0, accepted = 0;
    for (const auto& c : result.cross) {
        verified += c.refinement.accepted;
        accepted += c.accepted;
    }
    out << "cross-session closures: " << result.cross.size() << " candidates, " << verified << " verified in 3D, " << accepted
        << " accepted\n"
        << "joint map: " << result.joint_map_points << " points; written to " << folder.string() << '\n';
}

MergeResult MergeRunFolders(const std::vector<fs::path>& runs, const fs::path& out, bool force,
                            const std::vector<std::string>& overrides, std::ostream& log, std::ostream& out_stream,
                            bool allow_incomplete) {
    auto sessions = LoadSessionRuns(runs, allow_incomplete, &log);
    const PipelineConfig config = MergeConfig(sessions.front(), overrides);
    MergeResult result = MergeSessions(std::move(sessions), config, log);
    WriteMerge(out, force, result, config);
    PrintMergeSummary(out_stream, result, out);
    return result;
}

}  // namespace revisit
