#pragma once
/// `revisit run`: a dataset streamed through odometry, local maps, closures, refinement and the pose
/// graph, into a run folder; then evaluation (when ground truth exists) and the report.
#include <filesystem>
#include <memory>
#include <optional>
#include <ostream>

#include "config/config.hpp"
#include "pipeline/evaluation_pass.hpp"
#include "runfolder/run_folder.hpp"
#include "runfolder/run_state.hpp"

namespace revisit {

enum class PoseSource {
    kOdometry,  ///< our LiDAR odometry
    kDataset,   ///< the dataset's reference poses
    kPrior,     ///< the dataset's odometry prior (wheel odometry, a bag's odometry topic) as it is
    kFile,      ///< a KITTI or TUM trajectory file
};

struct RunOptions {
    std::filesystem::path dataset;
    std::filesystem::path out;          ///< the run folder
    PoseSource poses = PoseSource::kOdometry;
    std::filesystem::path poses_file;   ///< kFile
    std::filesystem::path gt_file;      ///< ground truth (KITTI or TUM), else the dataset's own poses
    std::size_t from = 0;               ///< first scan index read
    std::optional<std::size_t> to;      ///< last scan index read (inclusive)
    bool force = false;
    bool quiet = false;
    bool allow_truncated = false;       ///< a damaged rawlog ends the run where reading stopped (run.json: truncated)
};

/// Runs everything and writes the run folder. Progress and the summary go to `log`. Ctrl-C stops
/// reading; what was computed is written and run.json says "complete": false. The state's closures
/// within one session carry no keypoints: they are their maps' in database.bin. With `evaluation_pass`
/// and reference poses, the evaluation's share of each scan is made as the scans are read and handed
/// over there (EvaluateRun takes it).
RunState RunPipeline(const RunOptions& options, const PipelineConfig& config, std::ostream& log,
                     std::unique_ptr<EvaluationPass>* evaluation_pass = nullptr);

/// Throws ConfigError for --to < --from and DatasetError for --from past the end (when the dataset's
/// length is known before reading; rawlogs are checked after reading).
void CheckScanRange(const RunOptions& options, std::optional<std::size_t> num_scans);

/// The run's options as stored in run.json, so `revisit eval` can re-read the same scans.
void WriteRunOptions(const RunFolder& run, const RunOptions& options);
RunOptions ReadRunOptions(const RunFolder& run);

/// Peak resident memory of this process [KiB].
std::size_t PeakRssKb();

}  // namespace revisit
