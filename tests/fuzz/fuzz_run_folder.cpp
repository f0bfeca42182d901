/// libFuzzer: a run folder's files as `revisit report` / `eval` read them back. A valid minimal run
/// folder is made once; the first byte picks which of its files the rest of the input replaces.
#include <fstream>

#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "fuzz_support.hpp"
#include "runfolder/run_files.hpp"
#include "runfolder/run_folder.hpp"

namespace {
namespace fs = std::filesystem;

/// A run of 2 scans, 1 map and no closures, as WriteRunState writes it.
const revisit::RunFolder& ValidRun() {
    static const revisit::RunFolder run = [] {
        revisit::RunFolder folder(revisit::fuzz::Scratch() / "run");
        fs::create_directories(folder.root() / "closures");
        revisit::RunState state;
        state.dataset = "seq";
        state.format = "kitti";
        state.poses_source = "odometry";
        state.complete = true;
        state.timestamps = {0.0, 0.1};
        state.odometry = state.corrected = revisit::Poses(2, Eigen::Isometry3d::Identity());
        revisit::MapRecordSummary map;
        map.last_scan = 1;
        map.density_resolution = 0.5;
        state.maps = {map};
        state.timings["read"] = {1.0, 2};
        revisit::WriteRunState(folder, state);
        // Without its `files` table (as a run of an earlier version): a replaced file reaches its parser
        // instead of stopping at the size check; the table's own checks are fuzzed through run.json.
        nlohmann::json info;
        std::ifstream(folder.run_info()) >> info;
        info.erase("files");
        std::ofstream(folder.run_info(), std::ios::trunc) << info.dump(2) << '\n';
        return folder;
    }();
    return run;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    if (size < 1) return 0;
    using namespace revisit;
    const RunFolder& run = ValidRun();
    const fs::path files[] = {run.run_info(), run.odometry_tum(), run.corrected_kitti(), run.local_maps_csv(),
                              run.closures_csv(), run.timings_json(), run.root() / "closures" / "0000.json"};
    const fs::path& target = files[data[0] % 7];
    std::string original;
    if (fs::exists(target)) {
        std::ifstream in(target, std::ios::binary);
        original.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    }
    fuzz::WriteInput(target, data + 1, size - 1);
    try {
        if (target.extension() == ".json" && target.parent_path().filename() == "closures") {
            Closure closure;
            ReadClosureDetail(target, closure, 1000, 1000);  // the seed run's maps hold fewer
        } else {
            ReadRunState(run);
        }
    } catch (const DatasetError&) {
    }
    if (original.empty()) fs::remove(target);
    else std::ofstream(target, std::ios::binary) << original;
    return 0;
}
