#pragma once
/// Several finished runs as sessions of one map (issue 20): cross-session closures found in the runs'
/// saved databases and verified as in-session ones are (RANSAC 2D, 3D refinement, PCM per pair of
/// sessions, robust graph), one multi-session pose graph, each session's trajectory in the common frame
/// (the anchor session's odometry frame), the joint map. `revisit merge` and `revisit run --against`.
#include <filesystem>
#include <optional>
#include <ostream>
#include <vector>

#include "optimization/multi_session_graph.hpp"
#include "config/config.hpp"
#include "pipeline/pipeline.hpp"
#include "runfolder/run_folder.hpp"
#include "runfolder/run_state.hpp"

namespace revisit {

/// One finished run as a session.
struct SessionRun {
    std::filesystem::path folder;
    RunOptions options;  ///< what was read: dataset, --from, --to
    RunState state;
};

/// Opens a finished run; throws DatasetError naming the folder or the file that is missing or corrupt
/// (run.json, run_options.json, the trajectories, local_maps.csv, closures.csv, database.bin). An
/// interrupted run (run.json: complete = false) covers only part of its data: refused, naming it,
/// unless `allow_incomplete` (--allow-incomplete), when `log` gets a warning naming it.
SessionRun LoadSessionRun(const std::filesystem::path& folder, bool allow_incomplete = false, std::ostream* log = nullptr);

/// The runs in their canonical order, whatever order they were given in: by dataset path, then
/// --from, --to, then folder. The first is the anchor: its odometry frame becomes the common frame.
/// Throws ConfigError when the same run folder is given twice.
std::vector<SessionRun> LoadSessionRuns(const std::vector<std::filesystem::path>& folders, bool allow_incomplete = false,
                                        std::ostream* log = nullptr);

/// A cross-session closure candidate and its verdict. `closure` ids are the runs' map ids.
struct CrossClosure {
    int query_session = 0;  ///< index into MergeResult::sessions
    int ref_session = 0;
    Closure closure;
    Eigen::Vector3d up_in_query = Eigen::Vector3d::UnitZ();  ///< the query map's vertical (UpInMap)
    RefinementResult refinement;
    bool accepted = false;  ///< refined, consistent and kept by the joint graph
    std::string reason;     ///< why not accepted
    double graph_weight = 0.0;
};

struct MergeResult {
    std::vector<SessionRun> sessions;  ///< canonical order, 0 = anchor
    std::vector<CrossClosure> cross;   ///< every candidate at or above the detector's inlier gate
    MultiSessionResult graph;
    std::vector<Poses> corrected;      ///< per session, per scan, in the common frame; empty when unconnected
    /// [m] APE RMSE of each session in the common frame, the common frame tied to the reference frame by
    /// the anchor's alignment only (no per-session alignment); empty without references.
    std::vector<std::optional<double>> ape_common;
    std::vector<std::optional<double>> ape_aligned;  ///< [m] the same after the session's own SE(3) alignment
    std::size_t joint_map_points = 0;
};

/// The configuration the sessions are merged with: the anchor's config.yaml, then `overrides`.
PipelineConfig MergeConfig(const SessionRun& anchor, const std::vector<std::string>& overrides);

/// Finds, verifies and optimizes (no files written). Throws DatasetError when a database cannot be
/// loaded under `config` (different closure settings: descriptors are not comparable).
MergeResult MergeSessions(std::vector<SessionRun> sessions, const PipelineConfig& config, std::ostream& log);

/// Writes sessions.json, cross_closures.csv, session_KK_poses_{kitti,tum}.txt (connected sessions) and
/// map_joint.ply into `out` (created; a non-empty folder only with `force`). Fills joint_map_points.
void WriteMerge(const std::filesystem::path& out, bool force, MergeResult& result, const PipelineConfig& config);

/// Per session: connected or not, closures, APE; then the cross-closure counts and the output folder.
void PrintMergeSummary(std::ostream& out, const MergeResult& result, const std::filesystem::path& folder);

/// `revisit merge` and `run --against`: loads the runs, merges with the anchor's configuration plus
/// `overrides`, writes `out`, prints the summary on `out_stream`. Returns the result.
MergeResult MergeRunFolders(const std::vector<std::filesystem::path>& runs, const std::filesystem::path& out, bool force,
                            const std::vector<std::string>& overrides, std::ostream& log, std::ostream& out_stream,
                            bool allow_incomplete = false);

}  // namespace revisit
