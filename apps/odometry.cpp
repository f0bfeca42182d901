/// `revisit odometry DATASET --out DIR`: our LiDAR odometry alone, poses in KITTI and TUM formats.
#include <chrono>
#include <iostream>

#include "commands.hpp"
#include "core/owned_files.hpp"
#include "io/output_folder.hpp"
#include "io/reader.hpp"
#include "io/trajectory_io.hpp"
#include "odometry/lidar_odometry.hpp"
#include "pipeline/interrupt.hpp"
#include "pipeline/odometry_stages.hpp"
#include "pipeline/progress.hpp"
#include "run_options.hpp"

namespace revisit::app {
namespace {
constexpr std::size_t kShownWarnings = 10;  ///< frames that fell back, shown one by one; the rest are counted
struct OdometryOptions {
    std::string dataset, out;
    ConfigOptions config;
    bool force = false, quiet = false;
};

int RunOdometry(const OdometryOptions& o) {
    RefuseOutputInOrOverInput(o.dataset, o.out);  // before anything is read, even with --force
    const PipelineConfig config = ResolveConfigFor(o.config, o.dataset, std::cerr);
    const auto threads = LimitThreads(o.config.threads);
    const ReaderOptions reader_options = MakeReaderOptions(config.input);
    auto reader = OpenDataset(o.dataset, reader_options);
    PrepareOutputFolder(o.out, o.force);
    // An earlier odometry's poses must not outlive a run of this one that fails or is stopped early.
    for (const char* name : {"poses_kitti.txt", "poses_tum.txt"}) RemoveOwnFile(std::filesystem::path(o.out) / name);
    OdometryStages stages(config);
    const LidarOdometry& odometry = stages.odometry();
    Trajectory trajectory;
    Progress progress(std::cerr, Progress::DetectMode(o.quiet), reader->Info().num_scans);
    InstallInterruptHandler();
    const auto start = std::chrono::steady_clock::now();
    const auto next = [&]() -> std::optional<Scan> { return InterruptRequested() ? std::nullopt : reader->Next(); };
    RunOdometryStages(stages, next, [&](OdometryStages::Item& item, const Eigen::Isometry3d& T_world_sensor) {
        trajectory.poses.push_back(T_world_sensor);
        if (item.update) progress.Message(DescribeUpdate(*item.update));
        if (!odometry.LastStats().warning.empty() && odometry.NumDegenerateFrames() <= kShownWarnings) {
            progress.Message("warning: " + odometry.LastStats().warning);
        }
        trajectory.timestamps.push_back(item.scan.timestamp);
        progress.Update(trajectory.size());
    });
    progress.Finish(trajectory.size());
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const std::filesystem::path out(o.out);
    WriteKittiPoses(out / "poses_kitti.txt", trajectory.poses);
    WriteTumPoses(out / "poses_tum.txt", trajectory);
    std::cout << "odometry: " << trajectory.size() << " scans in " << seconds << " s ("
              << (seconds > 0 ? trajectory.size() / seconds : 0.0) << " scans/s), " << PathLength(trajectory.poses)
              << " m; " << odometry.NumDegenerateFrames() << " scans kept the motion prediction\n"
              << "wrote " << (out / "poses_kitti.txt").string() << " and " << (out / "poses_tum.txt").string() << '\n';
    return InterruptRequested() ? 130 : 0;
}
}  // namespace

void AddOdometryCommand(CLI::App& root, Action& action) {
    auto o = std::make_shared<OdometryOptions>();
    auto* cmd = root.add_subcommand("odometry", "Run the LiDAR odometry alone and write its poses");
    cmd->footer(
        "KISS-ICP-class scan-to-map ICP (docs/method.md). Writes OUT/poses_kitti.txt (3x4 per line) and\n"
        "OUT/poses_tum.txt (t x y z qx qy qz qw), poses of the sensor in the first scan's frame.\n"
        "Examples:\n"
        "  revisit odometry ~/kitti/sequences/00 --config kitti --out odo00\n"
        "  revisit odometry intel.rawlog --config indoor2d --out odo_intel --threads 1");
    cmd->add_option("dataset", o->dataset, "KITTI folder, .pcd/.ply folder, or .rawlog[.gz]")->required();
    cmd->add_option("--out", o->out, "output folder")->required();
    AddConfigOptions(*cmd, o->config);
    cmd->add_flag("--force", o->force, "write into an existing non-empty folder");
    cmd->add_flag("--quiet", o->quiet, "no progress output");
    cmd->callback([o, &action] { action = [o] { return RunOdometry(*o); }; });
}

}  // namespace revisit::app
