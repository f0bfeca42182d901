/// `revisit`: loop closures for range-sensor sequences. Parses, dispatches, reports errors.
#include <iostream>

#include "commands.hpp"
#include "core/allocator.hpp"
#include "core/printable.hpp"
#include "sim/sim_reader.hpp"

int main(int argc, char** argv) {
    revisit::TuneAllocator();
    revisit::FilterTerminalOutput();  // labels and names from the data never drive the terminal
    revisit::RegisterSimulatorDatasets();  // `sim:PRESET` wherever a dataset is named
    CLI::App root{
        "revisit finds loop closures in LiDAR and 2D-laser sequences and corrects the drifted trajectory.\n"
        "Datasets: KITTI-style folders (velodyne/*.bin), folders of .pcd/.ply scans, MRPT rawlogs, ROS bags\n"
        "(.bag, .mcap, rosbag2 folders), CARMEN logs, MulRan, Newer College, NCLT and HeLiPR folders, and the\n"
        "simulator itself (sim:PRESET, e.g. sim:demo: scans made as they are read, nothing on disk).\n"
        "Run `revisit SUBCOMMAND --help` for each command's options and examples.",
        "revisit"};
    root.require_subcommand(1);
    root.set_version_flag("--version", "revisit 0.1.0");
    revisit::app::Action action;
    revisit::app::AddDemoCommand(root, action);
    revisit::app::AddRunCommand(root, action);
    revisit::app::AddInfoCommand(root, action);
    revisit::app::AddSimulateCommand(root, action);
    revisit::app::AddOdometryCommand(root, action);
    revisit::app::AddEvalCommand(root, action);
    revisit::app::AddReportCommands(root, action);
    revisit::app::AddConvertCommand(root, action);
    revisit::app::AddExportCommand(root, action);
    revisit::app::AddConfigCommand(root, action);
    revisit::app::AddBenchCommand(root, action);
    revisit::app::AddMergeCommand(root, action);
    revisit::app::AddBatchCommand(root, action);
    try {
        root.parse(argc, argv);
        return action ? action() : 0;
    } catch (const CLI::ParseError& e) {
        return root.exit(e);
    } catch (const std::exception& e) {
        revisit::app::EndProgress();
        std::cerr << "revisit: " << e.what() << '\n';
        return 1;
    }
}
