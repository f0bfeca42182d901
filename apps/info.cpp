/// `revisit info DATASET`: what is in a dataset, read in one streaming pass.
#include <cstdio>
#include <iostream>

#include "commands.hpp"
#include "core/printable.hpp"
#include "io/dataset_summary.hpp"
#include "settings/auto_settings.hpp"

namespace revisit::app {
namespace {
struct InfoOptions {
    std::string dataset;
    std::string sensor;
    std::string poses;
    std::string topic;
};

/// A ROS bag's topics (a HeLiPR sequence's LiDAR folders) and the role each gets.
void PrintTopics(std::ostream& out, const std::vector<TopicSummary>& topics) {
    if (topics.empty()) return;
    out << "\ntopics:\n";
    for (const auto& t : topics) {
        char rate[32];
        std::snprintf(rate, sizeof rate, "%.2f Hz", t.rate_hz);
        out << "  " << PrintableField(t.name) << "  " << PrintableField(t.type) << "  " << t.messages << " messages  " << rate << "  -> " << t.role << '\n';
    }
}

int RunInfo(const InfoOptions& options) {
    ReaderOptions reader_options;
    reader_options.sensor_label = options.sensor;
    reader_options.poses_file = options.poses;
    reader_options.points_topic = options.topic;
    auto reader = OpenDataset(options.dataset, reader_options);
    const auto summary = Summarize(*reader, 50.0, [](std::size_t n) { ShowProgress("reading: " + std::to_string(n) + " scans"); });
    EndProgress();
    PrintSummary(std::cout, summary);
    PrintTopics(std::cout, reader->Info().topics);
    if (summary.num_scans > 0) {
        // What `revisit run` would derive from the first scans: sensor geometry, ranges, settings.
        PipelineConfig config;
        config.input.sensor_label = options.sensor;
        config.input.topic = options.topic;
        std::cout << '\n';
        PrintAutoSettings(std::cout, ConfigureFromData(config, options.dataset), options.dataset);
    }
    if (summary.num_scans == 0) {
        std::cerr << "revisit: " << options.dataset << ": no range scans found (nothing revisit can use)\n";
        return 1;
    }
    return 0;
}
}  // namespace

void AddInfoCommand(CLI::App& root, Action& action) {
    auto options = std::make_shared<InfoOptions>();
    auto* cmd = root.add_subcommand("info", "Describe a dataset: format, sensors, scans, points, poses, loops");
    cmd->footer(
        "Reads every scan once, one at a time (memory stays small).\n"
        "Examples:\n"
        "  revisit info ~/kitti/sequences/00\n"
        "  revisit info /usr/share/mrpt/datasets/2006-01ENE-21-SENA_Telecom\\ Faculty_one_loop_only.rawlog\n"
        "  revisit info scans_pcd/ --poses gt_tum.txt\n"
        "  revisit info recording.mcap   (also lists the topics and the role each gets)");
    cmd->add_option("dataset", options->dataset, "KITTI folder, folder of .pcd/.ply, .rawlog[.gz] file, or ROS bag (.mcap, .bag, rosbag2 folder)")->required();
    cmd->add_option("--sensor", options->sensor, "rawlogs: only scans with this sensor label; HeLiPR: the LiDAR (Ouster, Velodyne, Avia, Aeva)");
    cmd->add_option("--topic", options->topic, "ROS bags: the scan topic (when several fit)");
    cmd->add_option("--poses", options->poses, "reference trajectory (KITTI 3x4 or TUM) overriding the dataset's own");
    cmd->callback([options, &action] { action = [options] { return RunInfo(*options); }; });
}

}  // namespace revisit::app
