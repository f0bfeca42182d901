#include "exports/run_exports.hpp"

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "exports/closures_json.hpp"
#include "exports/pose_graph_export.hpp"
#include "exports/run_occupancy.hpp"
#include "runfolder/run_files.hpp"

namespace revisit {
namespace fs = std::filesystem;

void WriteRunExports(const RunFolder& run, const RunState& state, const PipelineConfig& config,
                     const OccupancyProgress& on_occupancy_map) {
    const ExportGraph graph = RunPoseGraph(state, config, false);
    WriteFileAtomically(run.root() / "pose_graph.g2o", [&](std::ostream& out) { WriteG2o(out, graph); });
    WriteFileAtomically(run.root() / "closures.json", [&](std::ostream& out) { WriteClosuresJson(out, state, config); });
    WriteRunOccupancy(run, state, config, run.root() / "occupancy.png", on_occupancy_map);
}

fs::path ExportRun(const fs::path& run_folder, const ExportOptions& options) {
    if (options.format != "g2o" && options.format != "closures-json" && options.format != "occupancy") {
        throw ConfigError("--format " + options.format + ": expected g2o, closures-json or occupancy");
    }
    if (options.per_scan && options.format != "g2o") throw ConfigError("--per-scan applies to --format g2o only");
    const RunFolder run = RunFolder::Open(run_folder);
    RunState state = ReadRunState(run, false);
    for (const auto& entry : options.overrides) {
        if (entry.rfind("occupancy.", 0) != 0) {
            throw ConfigError("--set " + entry + ": export takes occupancy.* keys only; the graph and the closures are the run's");
        }
    }
    const PipelineConfig config = LoadConfig({run.config().string()}, options.overrides);
    // The registration's information is not in closures.csv: the run recorded it in closures.json.
    const fs::path recorded = run.root() / "closures.json";
    if (config.graph_noise.closure_information_from_registration) {
        if (!fs::exists(recorded)) throw DatasetError(recorded, "missing: the closures' information matrices came from their registrations and only closures.json recorded them");
        ReadClosureInformation(recorded, state);
    }
    fs::path out = options.out;
    if (options.format == "occupancy") {
        // The image and its YAML go together; the YAML names the image relative to itself.
        if (out.empty()) out = run.root() / "occupancy.png";
        if (out.extension() != ".png" && out.extension() != ".pgm") {
            throw ConfigError("--out " + out.string() + ": the occupancy image is a .png or a .pgm (its .yaml goes beside it)");
        }
        return WriteRunOccupancy(run, state, config, out, options.on_occupancy_map);
    }
    if (out.empty()) {
        out = run.root() / (options.format == "closures-json" ? "closures.json" : options.per_scan ? "pose_graph_scans.g2o" : "pose_graph.g2o");
    }
    if (options.format == "closures-json") {
        WriteFileAtomically(out, [&](std::ostream& stream) { WriteClosuresJson(stream, state, config); });
    } else {
        const ExportGraph graph = RunPoseGraph(state, config, options.per_scan);
        WriteFileAtomically(out, [&](std::ostream& stream) { WriteG2o(stream, graph); });
    }
    return out;
}

}  // namespace revisit
