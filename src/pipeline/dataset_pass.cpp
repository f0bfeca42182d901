#include "pipeline/dataset_pass.hpp"

#include <algorithm>
#include <utility>

#include "evaluation/scan_context.hpp"
#include "evaluation/segment_voxel_file.hpp"
#include "io/prefetch_reader.hpp"
#include "io/reader.hpp"
#include "pipeline/covered_run.hpp"
#include "pipeline/progress.hpp"
#include "pipeline/read_from.hpp"

namespace revisit {
namespace fs = std::filesystem;

namespace {

bool SameSegments(const std::vector<GtSegment>& a, const std::vector<GtSegment>& b) {
    return std::equal(a.begin(), a.end(), b.begin(), b.end(), [](const GtSegment& x, const GtSegment& y) {
        return x.first_scan == y.first_scan && x.last_scan == y.last_scan && x.start_travel == y.start_travel;
    });
}

/// The ground truth from the segments' stored sets: each is read when a pair needs it, and a bounded
/// number stay in memory (a long drive's revisits would keep most of them until its end).
GtClosures GroundTruthFromStoredSets(GroundTruthBuilder& builder, const SegmentVoxelFile& stored, Progress::Mode mode,
                                     std::ostream& log) {
    constexpr std::size_t kSetBudget = std::size_t{64} << 20;  // [bytes]
    builder.LoadSetsFrom([&stored](std::size_t s) { return stored.Load(s); }, kSetBudget);
    builder.BoundOverlapsWith([&stored](std::size_t s) { return stored.LoadColumns(s); });
    Progress progress(log, mode, builder.segments().size(), "segments (ground truth)");
    builder.OnSettled([&progress](std::size_t settled) { progress.Update(settled); });
    GtClosures closures = builder.Finish();
    progress.Finish(builder.segments().size());
    return closures;
}

/// The pass from what the chain made of every scan (EvaluationPass); nullopt when its segments are not
/// the reference's (the caller then reads the data).
std::optional<DatasetPass> PassFromChain(EvaluationPass& chain, const Poses& reference, const PipelineConfig& config,
                                         const std::optional<GtClosures>& cached, Progress::Mode mode, std::ostream& log) {
    DatasetPass pass;
    if (cached) {
        pass.ground_truth = *cached;
    } else {
        GroundTruthBuilder builder(reference, config.ground_truth);
        const SegmentVoxelFile& stored = chain.segment_voxels();
        const std::vector<GtSegment>& segments = builder.segments();
        if (!SameSegments(segments, stored.segments())) {
            log << "note: the chain's ground-truth segments differ from the reference's: reading the data again\n";
            return std::nullopt;
        }
        pass.ground_truth = GroundTruthFromStoredSets(builder, stored, mode, log);
    }
    if (config.output.scan_context) pass.scan_context = chain.TakeScanContext();
    return pass;
}

}  // namespace

/// `reference` holds a pose per evaluated scan, `scans` each one's position in the run (empty: every
/// scan of the run, `run_scans` of them, is evaluated). The scratch files go to `scratch_dir`.
DatasetPass ReadDatasetPass(const Poses& reference, const std::vector<std::size_t>& scans, std::size_t run_scans,
                            const RunOptions& options, const PipelineConfig& config, const std::optional<GtClosures>& cached,
                            const fs::path& scratch_dir, EvaluationPass* chain, std::ostream& log) {
    if (chain && scans.empty() && reference.size() == run_scans && chain->Covers(run_scans)) {
        if (auto from_chain = PassFromChain(*chain, reference, config, cached, Progress::DetectMode(options.quiet), log)) return std::move(*from_chain);
    }
    DatasetPass pass;
    const bool need_scan_context = config.output.scan_context;
    if (need_scan_context) {
        pass.scan_context = std::make_unique<ScanContextFile>(scratch_dir / "scan_context.scratch", config.scan_context.num_rings,
                                                              config.scan_context.num_sectors);
    }
    if (cached) pass.ground_truth = *cached;
    if (cached && !need_scan_context) return pass;
    ReaderOptions reader_options = MakeReaderOptions(config.input);
    reader_options.allow_truncated = options.allow_truncated;  // the same scans the run read
    const std::unique_ptr<Reader> reader = std::make_unique<PrefetchReader>(OpenDataset(options.dataset, reader_options), 2);
    GroundTruthBuilder builder(reference, config.ground_truth);
    // Each segment's set goes to a scratch file of the run folder as the chain's pass stores it (the
    // scans of segments in no candidate pair add nothing), and the ground truth reads them back.
    std::unique_ptr<SegmentVoxelFile> sets;
    if (!cached) sets = std::make_unique<SegmentVoxelFile>(scratch_dir / "segment_voxels.scratch", config.ground_truth.segment_length);
    Progress progress(log, Progress::DetectMode(options.quiet), run_scans, "scans (evaluation)");
    std::size_t position = 0, evaluated = 0;  // in the run; in `reference`
    while (position < run_scans) {
        auto scan = NextFrom(*reader, options.from, progress, Progress::DetectMode(options.quiet), log);
        if (!scan) break;
        const bool is_evaluated = evaluated < reference.size() && RunScan(scans, evaluated) == position;
        if (is_evaluated && sets) {
            const Eigen::Isometry3d& T_world_sensor = reference[evaluated];
            sets->Add(T_world_sensor, builder.NeedsScan(evaluated) ? ScanVoxels(T_world_sensor, scan->points, config.ground_truth.voxel_size,
                                                                                config.ground_truth.voxel_subsample)
                                                                     : PackedVoxels{});
        }
        evaluated += is_evaluated;
        if (need_scan_context) pass.scan_context->Add(MakeScanContext(scan->points, config.scan_context));
        progress.Update(++position);
    }
    progress.Finish(position);
    if (sets) {
        // Scans the data no longer has count as empty, as they would have without a file.
        for (; evaluated < reference.size(); ++evaluated) sets->Add(reference[evaluated], PackedVoxels{});
        sets->Finish();
        pass.ground_truth = GroundTruthFromStoredSets(builder, *sets, Progress::DetectMode(options.quiet), log);
    }
    return pass;
}

}  // namespace revisit
