#include "pipeline/pipeline.hpp"

#include "core/cpu_time.hpp"

#include <sys/resource.h>

#include <nlohmann/json.hpp>

#include <chrono>
#include <fstream>
#include <iomanip>
#include <sstream>

#include <tbb/parallel_pipeline.h>
#include <tbb/task_arena.h>

#include "closures/database_io.hpp"
#include "core/allocator.hpp"
#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "exports/run_exports.hpp"
#include "io/output_folder.hpp"
#include "io/prefetch_reader.hpp"
#include "io/reader.hpp"
#include "io/trajectory_io.hpp"
#include "odometry/lidar_odometry.hpp"
#include "runfolder/folder_map_store.hpp"
#include "runfolder/global_map.hpp"
#include "runfolder/map_points_file.hpp"
#include "runfolder/planar_scans.hpp"
#include "pipeline/interrupt.hpp"
#include "pipeline/online.hpp"
#include "pipeline/progress.hpp"
#include "pipeline/read_from.hpp"
#include "core/input_file.hpp"
#include "runfolder/json_file.hpp"
#include "runfolder/run_files.hpp"
#include "pipeline/odometry_stages.hpp"
#include "pipeline/pose_file_source.hpp"

namespace revisit {
namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;
constexpr std::size_t kShownFallbacks = 10;  ///< odometry fallbacks shown one by one; all are in run.json
/// Scans between reading and the closure pipeline: the odometry runs ahead while a map closes and
/// prepares scans ahead of their registration. Fewer than the odometry alone takes
/// (kOdometryScansInFlight): here the closure pipeline keeps the second core busy, and each scan in
/// flight holds its points twice (the demo: 6 scans, peak memory 246-249 MiB; 4 scans, 238-243 MiB).
constexpr std::size_t kScansInFlight = 4;

std::size_t PeakRssKb() {
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    return static_cast<std::size_t>(usage.ru_maxrss);
}

namespace {

/// A scan on its way through the stages: the odometry's share and the evaluation's (EvaluationPass).
struct StagedScan {
    OdometryStages::Item item;
    EvaluationPass::ScanPart evaluation;
    double evaluation_ms = 0.0;  ///< [ms] CPU time of its share, made ahead in the parallel stage
};

/// A scan with its pose, on its way from the odometry to the closure pipeline.
struct PosedScan {
    std::size_t position = 0;  ///< among the scans processed
    std::vector<Eigen::Vector3f> points;  ///< in the sensor frame (deskewed by the odometry)
    Eigen::Isometry3d T_world_sensor = Eigen::Isometry3d::Identity();
    std::vector<std::string> messages;  ///< printed with the progress, in order
};

const char* PoseSourceName(PoseSource source) {
    switch (source) {
        case PoseSource::kOdometry: return "odometry";
        case PoseSource::kDataset: return "dataset";
        case PoseSource::kPrior: return "prior";
        default: return "file";
    }
}

std::vector<Eigen::Vector3f> ToFloat(const std::vector<Eigen::Vector3d>& points) {
    std::vector<Eigen::Vector3f> out(points.size());
    for (std::size_t i = 0; i < points.size(); ++i) out[i] = points[i].cast<float>();
    return out;
}

void WriteBytes(const fs::path& file, const std::vector<std::uint8_t>& bytes) {
    WriteFileAtomically(file, std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
}

}  // namespace

void CheckScanRange(const RunOptions& options, std::optional<std::size_t> num_scans) {
    if (options.to && *options.to < options.from) {
        throw ConfigError("--from " + std::to_string(options.from) + " --to " + std::to_string(*options.to) +
                          ": an empty range (--to is the last scan, inclusive, and must be >= --from)");
    }
    if (num_scans && options.from >= *num_scans) {
        throw DatasetError(options.dataset, "--from " + std::to_string(options.from) + " is past the end: the dataset has " +
                                                std::to_string(*num_scans) + " scans (0 .. " +
                                                std::to_string(*num_scans == 0 ? 0 : *num_scans - 1) + ")");
    }
}

void WriteRunOptions(const RunFolder& run, const RunOptions& o) {
    nlohmann::json j = {{"poses", PoseSourceName(o.poses)}, {"from", o.from},
                        {"to", o.to ? nlohmann::json(*o.to) : nlohmann::json(nullptr)}, {"allow_truncated", o.allow_truncated}};
    // Paths keep their bytes even when they are not UTF-8: `revisit eval` opens them again.
    PutPath(j, "dataset", DatasetName(o.dataset));
    PutPath(j, "poses_file", o.poses_file.empty() ? fs::path() : fs::absolute(o.poses_file));
    PutPath(j, "gt_file", o.gt_file.empty() ? fs::path() : fs::absolute(o.gt_file));
    WriteJsonFile(run.root() / "run_options.json", j);
}

RunOptions ReadRunOptions(const RunFolder& run) {
    const fs::path file = run.root() / "run_options.json";
    std::ifstream in = OpenForReading(file);
    try {
        const auto j = nlohmann::json::parse(in);
        RunOptions o;
        o.dataset = GetPath(j, "dataset");
        const std::string poses = j.at("poses").get<std::string>();
        o.poses = poses == "odometry" ? PoseSource::kOdometry
                  : poses == "dataset"  ? PoseSource::kDataset
                  : poses == "prior"    ? PoseSource::kPrior
                                        : PoseSource::kFile;
        o.poses_file = GetPath(j, "poses_file");
        o.gt_file = GetPath(j, "gt_file");
        o.from = j.at("from").get<std::size_t>();
        if (!j.at("to").is_null()) o.to = j.at("to").get<std::size_t>();
        o.allow_truncated = j.value("allow_truncated", false);
        o.out = run.root();
        return o;
    } catch (const nlohmann::json::exception& e) {
        throw DatasetError(file, std::string("malformed: ") + e.what());
    }
}

RunState RunPipeline(const RunOptions& options, const PipelineConfig& config, std::ostream& log,
                     std::unique_ptr<EvaluationPass>* evaluation_pass) {
    const auto run_start = Clock::now();
    // Before anything is opened, even with --force: a run folder in the dataset would become part of it.
    if (!options.out.empty()) RefuseOutputInOrOverInput(options.dataset, options.out);
    ReaderOptions reader_options = MakeReaderOptions(config.input);
    reader_options.allow_truncated = options.allow_truncated;
    // Open every input before creating the run folder: bad input fails without leaving anything behind.
    // Read ahead on a thread of its own (two scans, same order): reading overlaps the processing.
    std::unique_ptr<Reader> reader = std::make_unique<PrefetchReader>(OpenDataset(options.dataset, reader_options), 2);
    const PoseFileSource pose_file(options.poses == PoseSource::kFile ? options.poses_file : fs::path(), "--poses",
                                   reader_options.pose_pairing);
    const PoseFileSource ground_truth(options.gt_file, "--gt", reader_options.pose_pairing);
    pose_file.CheckCount(reader->Info().num_scans);
    ground_truth.CheckCount(reader->Info().num_scans);
    CheckScanRange(options, reader->Info().num_scans);
    const RunFolder run = RunFolder::Create(options.out, options.force);
    WriteRunOptions(run, options);
    {
        std::string header;
        if (!config.derived.empty()) header = "# Settings derived from the data (revisit run prints why):\n";
        for (const auto& line : config.derived) header += "#   " + line + '\n';
        WriteFileAtomically(run.config(), header + DumpConfig(config));
    }

    // The ablation only matters when it can be scored.
    PipelineConfig effective = config;
    const bool expect_reference = ground_truth.active() || reader->Info().has_reference_poses;
    effective.output.elevation_ablation = config.output.elevation_ablation && expect_reference;
    ClosurePipeline pipeline(effective, MakeFolderMapStore(run, MapPointStep(config.output.map_voxel)));
    pipeline.on_map_closed = [&run](const LocalMap& map, const MapRecord& record) {
        if (!record.image_png.empty()) WriteBytes(run.map_density(map.id), record.image_png);
    };
    // The evaluation's share of each scan, made as the chain reads it, when the caller evaluates next.
    std::unique_ptr<EvaluationPass> pass;
    if (evaluation_pass && expect_reference) pass = std::make_unique<EvaluationPass>(run, config);
    std::optional<OdometryStages> odometry;
    if (options.poses == PoseSource::kOdometry) odometry.emplace(config);
    // A 2D laser's beams, kept per map for the occupancy grid's ray tracing at the corrected poses.
    std::optional<PlanarScanWriter> planar_scans;
    if (config.odometry.planar) planar_scans.emplace(run);

    RunState state;
    state.dataset = DatasetName(options.dataset);
    state.format = reader->Info().format;
    state.poses_source = options.poses == PoseSource::kFile ? options.poses_file.string() : PoseSourceName(options.poses);
    std::optional<std::size_t> total;
    if (reader->Info().num_scans) {
        const std::size_t last = std::min(*reader->Info().num_scans, options.to ? *options.to + 1 : *reader->Info().num_scans);
        total = last > options.from ? last - options.from : 0;
    }
    Progress progress(log, Progress::DetectMode(options.quiet), total);
    InstallInterruptHandler();
    // Reference poses as paired, per scan processed: a scan without one is left out of the metrics.
    Poses reference;
    std::vector<std::size_t> reference_scans;
    UnpairedScans unpaired;
    bool read_to_end = false;  // the reader ran out (not --to, not Ctrl-C): a KITTI file's count can be checked
    std::map<std::string, StageTimer> timings;
    const auto time = [](StageTimer& timer, Clock::time_point start) {
        timer.total_ms += std::chrono::duration<double, std::milli>(Clock::now() - start).count();
        timer.count++;
    };
    // Four stages (issue 19), on the same TBB threads (`--threads`): reading, in order; the odometry's
    // preparation of each scan (odometry_stages.hpp), several scans at once; its registration, in order;
    // the closure pipeline, in order. The odometry runs ahead while a map closes and never reads what
    // the closure pipeline does: the results are those of a loop. Each stage's parallel loops are
    // isolated, so a thread waiting inside one never picks up another stage's work (a map's detection
    // and verification take ~100 ms). Each timer is touched by one serial stage only.
    std::size_t accepted = 0;
    StageTimer read_timer, odometry_timer, prepare_timer, pass_timer;
    const auto reference_of = [&](const Scan& scan) {
        return ground_truth.active() ? ground_truth.At(scan.index, scan.timestamp) : scan.T_world_sensor;
    };
    const auto read = [&](tbb::flow_control& flow) -> StagedScan {
        const auto read_start = Clock::now();  // the wait for the read-ahead thread's scan
        StagedScan staged;
        OdometryStages::Item& item = staged.item;
        std::optional<Scan> scan =
            NextFrom(*reader, options.from, progress, Progress::DetectMode(options.quiet), log, [] { return InterruptRequested(); });
        time(read_timer, read_start);
        if (!scan) read_to_end = !InterruptRequested();
        if (!scan || InterruptRequested() || (options.to && scan->index > *options.to)) {
            flow.stop();
            return staged;
        }
        item.scan = std::move(*scan);
        if (odometry) odometry->Admit(item);
        return staged;
    };
    const auto prepare = [&](StagedScan staged) {
        if (odometry) OdometryStages::Prepare(staged.item);
        if (pass) {
            const double start = ThreadCpuSeconds();  // CPU: the evaluation's cost per scan, whatever the load
            staged.evaluation = pass->Prepare(staged.item.scan, reference_of(staged.item.scan));
            staged.evaluation_ms = 1e3 * (ThreadCpuSeconds() - start);
        }
        return staged;
    };
    const auto pose = [&](StagedScan staged) -> PosedScan {
        OdometryStages::Item& item = staged.item;
        if (pass) {
            const double start = ThreadCpuSeconds();
            pass->Add(std::move(staged.evaluation));
            pass_timer.total_ms += 1e3 * (ThreadCpuSeconds() - start) + staged.evaluation_ms;
            pass_timer.count++;
        }
        PosedScan posed;
        Scan& scan = item.scan;
        posed.position = state.odometry.size();
        if (odometry) {
            const auto odometry_start = Clock::now();
            posed.T_world_sensor = odometry->Register(item);
            const LidarOdometry& registered = odometry->odometry();
            posed.points = ToFloat(registered.LastDeskewedPoints());
            if (registered.LastStats().degenerate) {
                state.odometry_fallbacks.push_back(posed.position);
                if (state.odometry_fallbacks.size() <= kShownFallbacks) posed.messages.push_back("warning: " + registered.LastStats().warning);
            }
            if (item.update) {
                posed.messages.push_back(DescribeUpdate(*item.update));
                state.setting_updates.push_back(std::move(*item.update));
            }
            time(odometry_timer, odometry_start);
            prepare_timer.total_ms += item.prepare_ms;  // done ahead, alongside the stages
            prepare_timer.count++;
        } else if (options.poses == PoseSource::kDataset) {
            if (!scan.T_world_sensor) throw DatasetError(options.dataset, "scan " + std::to_string(scan.index) +
                                                                              " has no reference pose; use --poses odometry");
            posed.T_world_sensor = *scan.T_world_sensor;
            posed.points = std::move(scan.points);
        } else if (options.poses == PoseSource::kPrior) {
            if (!scan.T_odom_sensor) throw DatasetError(options.dataset, "scan " + std::to_string(scan.index) +
                                                                             " has no odometry prior; use --poses odometry");
            posed.T_world_sensor = *scan.T_odom_sensor;
            posed.points = std::move(scan.points);
        } else {
            posed.T_world_sensor = pose_file.Required(scan.index, scan.timestamp);
            posed.points = std::move(scan.points);
        }
        state.timestamps.push_back(scan.timestamp);
        state.odometry.push_back(posed.T_world_sensor);
        const auto paired = reference_of(scan);
        if (paired) {
            reference.push_back(*paired);
            reference_scans.push_back(posed.position);
        } else if (ground_truth.active() || reader->Info().has_reference_poses) {
            unpaired.Add(scan.index, scan.timestamp);
        }
        return posed;
    };
    const auto close_maps = [&](PosedScan posed) {
        for (const auto& line : posed.messages) progress.Message(line);
        tbb::this_task_arena::isolate([&] {
            for (const auto& c : pipeline.AddScan(posed.position, posed.points, posed.T_world_sensor).closures) accepted += c.accepted;
        });
        // The open map's id: the maps closed so far (a scan that closes a map starts the next one).
        if (planar_scans) planar_scans->Add(static_cast<int>(pipeline.maps().size()), posed.position, posed.points);
        progress.Update(posed.position + 1, "maps " + std::to_string(pipeline.maps().size()) + "  closures " + std::to_string(accepted));
    };
    tbb::parallel_pipeline(kScansInFlight, tbb::make_filter<void, StagedScan>(tbb::filter_mode::serial_in_order, read) &
                                               tbb::make_filter<StagedScan, StagedScan>(tbb::filter_mode::parallel, prepare) &
                                               tbb::make_filter<StagedScan, PosedScan>(tbb::filter_mode::serial_in_order, pose) &
                                               tbb::make_filter<PosedScan, void>(tbb::filter_mode::serial_in_order, close_maps));
    timings["read"] = read_timer;
    if (odometry_timer.count > 0) {
        timings["odometry"] = odometry_timer;
        timings["odometry.prepare"] = prepare_timer;
    }
    if (pass_timer.count > 0) timings["evaluation.pass"] = pass_timer;  // the evaluation's share, made by the chain
    state.complete = !InterruptRequested();
    state.truncated = reader->Info().truncated;
    // The reader goes before the closing stages: a simulated drive's world (hundreds of MB for a long
    // route) would otherwise stay beside the global map, the chain's peak of memory.
    const ReadStats read_stats = reader->Stats();
    reader.reset();
    if (pass) {
        pass->Finish();
        *evaluation_pass = std::move(pass);
    }
    if (state.odometry.empty() && state.complete) {
        // Only rawlogs get here with --from past the end: their length is known once read.
        throw DatasetError(options.dataset, options.from > 0 ? "--from " + std::to_string(options.from) +
                                                                   " is past the end: the dataset has " +
                                                                   std::to_string(read_stats.scans) + " scans"
                                                             : std::string("no scans read"));
    }
    if (planar_scans) planar_scans->Finish();
    // The last map, the proximity pass over every map and the final pose graph: minutes on a long run.
    if (!options.quiet) {
        progress.Message("revisit: " + std::to_string(state.odometry.size()) + " scans read; closing: the last map, the " +
                         "proximity pass over the corrected poses and the final pose graph");
    }
    CountedProgress final_pass(log, Progress::DetectMode(options.quiet), "map pairs (proximity pass)");
    pipeline.on_proximity_progress = std::ref(final_pass);
    for (const auto& c : pipeline.Finish().closures) accepted += c.accepted;
    pipeline.on_proximity_progress = nullptr;
    if (const auto gate = pipeline.RmsGateUpdate()) state.setting_updates.push_back(*gate);
    if (const auto& drift = pipeline.DriftCalibration()) state.setting_updates.push_back(*drift);
    progress.Finish(state.odometry.size(), "maps " + std::to_string(pipeline.maps().size()) + "  closures " +
                                               std::to_string(accepted));
    if (read_to_end) {
        // Rawlogs: their length is known once read.
        pose_file.CheckCount(read_stats.scans);
        ground_truth.CheckCount(read_stats.scans);
    }
    if (reference.size() == state.odometry.size()) {
        state.reference = std::move(reference);
    } else if (!reference.empty()) {
        state.reference = std::move(reference);
        state.reference_scans = std::move(reference_scans);
    }

    state.maps = pipeline.maps();
    state.closures = pipeline.TakeClosures();  // a pair within the session without keypoints: database.bin's
    state.comparisons = pipeline.TakeComparisons();
    state.map_of_scan = MapOfScan(state.maps, state.odometry.size());
    state.corrected = state.maps.empty() ? state.odometry : pipeline.CorrectTrajectory(state.odometry, state.map_of_scan);
    state.timings = pipeline.timings();
    for (const auto& [stage, timer] : timings) state.timings[stage] = timer;

    auto start = Clock::now();
    ReleaseFreeMemory();  // the global map is the chain's peak of memory: build it on a trimmed heap
    SaveDatabase(pipeline.detector(), run.database());
    const auto global_map = WriteGlobalMap(run, state, config.output.global_map_voxel, GlobalMapMaxPoints(config));
    if (global_map.voxel_size != config.output.global_map_voxel) {
        // A data-driven setting like the others: it applies to the whole map, so from scan 0.
        std::ostringstream reason;
        reason << "the corrected global map would pass output.global_map_max_points (" << config.output.global_map_max_points
               << "); " << global_map.points << " points at the doubled voxel";
        state.setting_updates.push_back({0, "output.global_map_voxel", config.output.global_map_voxel, global_map.voxel_size, reason.str()});
        log << "note: map_corrected.ply: output.global_map_voxel " << config.output.global_map_voxel << " -> " << global_map.voxel_size
            << " m to keep it within " << config.output.global_map_max_points << " points (" << global_map.points
            << "); --set output.global_map_voxel=... keeps a voxel as given\n";
    }
    time(state.timings["write"], start);
    state.wall_seconds = std::chrono::duration<double>(Clock::now() - run_start).count();
    state.peak_rss_kb = PeakRssKb();
    WriteRunState(run, state);
    // A long run's grid reads every map twice: a minute at 100,000 scans.
    CountedProgress occupancy(log, Progress::DetectMode(options.quiet), "map passes (occupancy grid)");
    WriteRunExports(run, state, config, std::ref(occupancy));
    if (!state.odometry_fallbacks.empty()) {
        log << "warning: the odometry fell back to the motion prediction on " << state.odometry_fallbacks.size() << " of "
            << state.odometry.size() << " scans" << (state.odometry_fallbacks.size() > kShownFallbacks ? " (the first shown above)" : "")
            << "; run.json lists them\n";
    }
    if (unpaired.count > 0) {
        log << "note: " << (ground_truth.active() ? options.gt_file.string() + ": " : std::string()) << unpaired.Describe()
            << (ground_truth.by_time() ? "; the reference: " + ground_truth.DescribeSpan() : std::string()) << '\n';
    }
    if (read_to_end && options.to && *options.to >= read_stats.scans) {
        // As --from past the end is an error: the range asked for is not silently shortened.
        log << "note: --to " << *options.to << " is past the end: the dataset has " << read_stats.scans
            << " scans; the run covers scans " << options.from << " .. " << read_stats.scans - 1 << '\n';
    }
    const std::string drops = DescribeDrops(read_stats);
    if (!drops.empty()) log << "note: " << drops << '\n';
    if (!state.truncated.empty()) {
        log << "warning: --allow-truncated: the input is damaged, the run covers the " << state.odometry.size()
            << " scans read before: " << state.truncated << " (run.json: truncated = true)\n";
    }
    if (!state.complete) log << "interrupted: wrote the " << state.odometry.size() << " scans processed so far (run.json: complete = false)\n";
    return state;
}

}  // namespace revisit
