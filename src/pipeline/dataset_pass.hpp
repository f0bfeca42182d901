#pragma once
/// The evaluation's pass over the scans (ground_truth_closures.hpp, scan_context.hpp): from what the chain
/// made of every scan (EvaluationPass) when it covers the run, else by reading the dataset again.
#include <filesystem>
#include <memory>
#include <optional>
#include <ostream>
#include <vector>

#include "config/config.hpp"
#include "core/trajectory.hpp"
#include "evaluation/ground_truth_closures.hpp"
#include "evaluation/scan_context_file.hpp"
#include "pipeline/evaluation_pass.hpp"
#include "pipeline/pipeline.hpp"

namespace revisit {

/// Ground-truth closures and ScanContext descriptors from one pass over the scans of the run.
struct DatasetPass {
    GtClosures ground_truth;  ///< over the evaluated scans (positions of `reference`)
    std::unique_ptr<ScanContextFile> scan_context;  ///< one per scan of the run; null when not asked for
};

/// `reference` holds a pose per evaluated scan, `scans` each one's position in the run (empty: every
/// scan of the run, `run_scans` of them, is evaluated). `cached`: the ground truth from the run
/// folder's cache (then only ScanContext's descriptors are made). `chain`: the chain's pass, used when
/// it covers every scan with the reference's segments. The scratch files go to `scratch_dir`.
DatasetPass ReadDatasetPass(const Poses& reference, const std::vector<std::size_t>& scans, std::size_t run_scans,
                            const RunOptions& options, const PipelineConfig& config, const std::optional<GtClosures>& cached,
                            const std::filesystem::path& scratch_dir, EvaluationPass* chain, std::ostream& log);

}  // namespace revisit
