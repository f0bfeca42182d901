#pragma once
/// Writing a run's state into its folder and reading it back (CSV and JSON that other tools read).
#include "runfolder/run_folder.hpp"
#include "runfolder/run_state.hpp"

namespace revisit {

/// poses_{odometry,corrected}_{kitti,tum}.txt, poses_reference_tum.txt, local_maps.csv,
/// closures.csv, closures/NNNN.json (matches and keypoints for the report), timings.json, run.json.
void WriteRunState(const RunFolder& run, const RunState& state);

/// Reads what WriteRunState wrote; throws DatasetError naming the file on anything malformed.
/// `closure_details`: also each closure's matches (closures/NNNN.json), which only the report draws; the
/// evaluation and the exports skip them (on a 100,000-scan run of older files: ~350 MB in memory).
RunState ReadRunState(const RunFolder& run, bool closure_details = true);

/// A pair within one session: both maps' keypoints are in that run's database.bin, so neither its
/// closure file nor a run's state keeps them (the report draws them from the database).
inline bool KeypointsInDatabase(const Closure& closure) { return closure.query_session == closure.ref_session; }

/// The closure's matches, and its keypoints when `with_keypoints` (the density detector's are the maps' in
/// database.bin: the report draws them from there). Reading checks every match against the file's
/// keypoints when it has them, else against the maps' keypoint counts (local_maps.csv).
void WriteClosureDetail(const std::filesystem::path& file, const Closure& closure, bool with_keypoints);
void ReadClosureDetail(const std::filesystem::path& file, Closure& closure, int num_query_keypoints, int num_ref_keypoints);

}  // namespace revisit
