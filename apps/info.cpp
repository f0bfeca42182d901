/// `revisit info DATASET`: what is in a dataset, read in one streaming pass.
#include <iostream>

#include "commands.hpp"
#include "io/dataset_summary.hpp"
#include "settings/auto_settings.hpp"

namespace revisit::app {
namespace {
struct InfoOptions {
    std::string dataset;
    std::string sensor;
    std::string poses;
};

int RunInfo(const InfoOptions& options) {
    ReaderOptions reader_options;
    reader_options.sensor_label = options.sensor;
    reader_options.poses_file = options.poses;
    auto reader = OpenDataset(options.dataset, reader_options);
    const auto summary = Summarize(*reader, 50.0, [](std::size_t n) { ShowProgress("reading: " + std::to_string(n) + " scans"); });
    EndProgress();
    PrintSummary(std::cout, summary);
    if (summary.num_scans > 0) {
        // What `revisit run` would derive from the first scans: sensor geometry, ranges, settings.
        PipelineConfig config;
        config.input.sensor_label = options.sensor;
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
        "  revisit info scans_pcd/ --poses gt_tum.txt");
    cmd->add_option("dataset", options->dataset, "KITTI folder, folder of .pcd/.ply, or .rawlog[.gz] file")->required();
    cmd->add_option("--sensor", options->sensor, "rawlogs: only scans with this sensor label");
    cmd->add_option("--poses", options->poses, "reference trajectory (KITTI 3x4 or TUM) overriding the dataset's own");
    cmd->callback([options, &action] { action = [options] { return RunInfo(*options); }; });
}

}  // namespace revisit::app
