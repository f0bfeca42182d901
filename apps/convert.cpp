/// `revisit convert IN OUT`: KITTI folder <-> MRPT rawlog (and .pcd/.ply folders -> either).
#include <iostream>

#include "commands.hpp"
#include "io/output_folder.hpp"
#include "io/reader.hpp"
#include "io/writer.hpp"

namespace revisit::app {
namespace {
struct ConvertOptions {
    std::string input, output, sensor, topic;
    bool force = false;
    bool planar = false;
    int beams = 360;
    double aperture_deg = 360.0;
};

int RunConvert(const ConvertOptions& options) {
    RefuseOutputOverInput(options.input, options.output);  // before anything is opened, even with --force
    ReaderOptions reader_options;
    reader_options.sensor_label = options.sensor;
    reader_options.points_topic = options.topic;
    auto reader = OpenDataset(options.input, reader_options);
    WriterOptions writer_options;
    writer_options.planar_as_range_scan = options.planar;
    writer_options.planar_beams = options.beams;
    writer_options.planar_aperture = options.aperture_deg * M_PI / 180.0;
    auto writer = CreateWriter(options.output, writer_options, options.force);
    std::size_t count = 0;
    while (auto scan = reader->Next()) {
        writer->Write(*scan);
        if (++count % 100 == 0) ShowProgress("converted " + std::to_string(count) + " scans");
    }
    writer->Finish();
    EndProgress();
    std::cout << "wrote " << count << " scans from " << options.input << " to " << options.output << '\n';
    const std::string drops = DescribeDrops(reader->Stats());
    if (!drops.empty()) std::cout << "note: " << drops << '\n';
    return count > 0 ? 0 : 1;
}
}  // namespace

void AddConvertCommand(CLI::App& root, Action& action) {
    auto options = std::make_shared<ConvertOptions>();
    auto* cmd = root.add_subcommand("convert", "Convert between KITTI folders and MRPT rawlogs");
    cmd->footer(
        "OUT ending in .rawlog or .rawlog.gz writes a rawlog (CObservationPointCloud per scan, reference\n"
        "poses as CObservationRobotPose 'GROUND_TRUTH', odometry priors kept); anything else writes a\n"
        "KITTI folder (velodyne/NNNNNN.bin, poses.txt, times.txt, identity calib.txt). Points are copied\n"
        "bit-exact. An existing non-empty OUT is refused unless --force.\n"
        "Examples:\n"
        "  revisit convert ~/kitti/sequences/00 seq00.rawlog.gz\n"
        "  revisit convert intel.rawlog intel_kitti/\n"
        "  revisit convert intel_kitti/ intel2d.rawlog --planar --beams 180 --aperture 180");
    cmd->add_option("input", options->input, "KITTI folder, .pcd/.ply folder, .rawlog[.gz], ROS bag (.mcap, .bag, rosbag2 folder), CARMEN log, or a MulRan, Newer College, NCLT or HeLiPR sequence folder")->required();
    cmd->add_option("output", options->output, "KITTI folder, or file ending in .rawlog / .rawlog.gz")->required();
    cmd->add_option("--sensor", options->sensor, "rawlog input: only scans with this sensor label; HeLiPR: the LiDAR (Ouster, Velodyne, Avia, Aeva)");
    cmd->add_option("--topic", options->topic, "ROS bag input: the scan topic (when several fit)");
    cmd->add_flag("--force", options->force, "write into an existing non-empty folder / overwrite a file");
    cmd->add_flag("--planar", options->planar, "rawlog output: store planar scans as CObservation2DRangeScan");
    cmd->add_option("--beams", options->beams, "with --planar: beams per scan")->check(CLI::Range(2, 100000));
    cmd->add_option("--aperture", options->aperture_deg, "with --planar: field of view [deg]")->check(CLI::Range(1.0, 360.0));
    cmd->callback([options, &action] { action = [options] { return RunConvert(*options); }; });
}

}  // namespace revisit::app
