/// The whole chain as `revisit run` runs it, on a simulated 64-beam city sequence written as a KITTI
/// folder: scans per second of RunPipeline, its stages per scan, evaluation + report, peak memory.
#include <map>
#include <sstream>

#include "bench_suite/cases.hpp"
#include "bench_suite/machine.hpp"
#include "pipeline/evaluate.hpp"
#include "pipeline/pipeline.hpp"
#include "pipeline/report_builder.hpp"
#include "sim/presets.hpp"

namespace revisit {

void EndToEndCases(const CaseContext& c) {
    SimConfig sim = SimPreset("city-64");
    sim.max_scans = c.scale.end_to_end_scans;
    const auto dataset = c.scratch_dir / "e2e_city64";
    const SimSummary summary = RunSimulation(sim, dataset, true);
    const std::string data_note = "city-64 preset, " + std::to_string(summary.scans) + " scans, " +
                                  std::to_string(int(summary.length)) + " m, " +
                                  std::to_string(summary.points / std::max<std::size_t>(1, summary.scans)) +
                                  " points/scan, default config, our odometry";
    const PipelineConfig config;
    std::map<std::string, std::vector<double>> stage_ms;
    std::vector<double> eval_report_ms;
    std::size_t closures = 0;
    const auto run = [&] {
        RunOptions options;
        options.dataset = dataset;
        options.out = c.scratch_dir / "e2e_run";
        options.force = true;
        options.quiet = true;
        std::ostringstream log;
        const RunState state = RunPipeline(options, config, log);
        const double scans = double(std::max<std::size_t>(1, state.odometry.size()));
        for (const auto& [stage, timer] : state.timings) stage_ms[stage].push_back(timer.total_ms / scans);
        closures = state.NumAccepted();
        const auto start = std::chrono::steady_clock::now();
        const RunFolder folder(options.out);
        EvaluateRun(folder, state, options, config, log);
        if (config.output.write_report) WriteRunReport(folder, log);
        eval_report_ms.push_back(
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count() / scans);
        return double(state.odometry.size());
    };
    // Peak memory is the process's: this group runs first in a suite so that it is the pipeline's.
    const MeasureConfig repeat{0, c.scale.end_to_end_repetitions};
    {
        Measurement measured = Measure("end_to_end/run scans", "scans/s", FigureKind::kItemsPerSecond, repeat, run);
        c.Add(std::move(measured), "RunPipeline (odometry, local maps, closures, refinement, pose graph, writing), " +
                                       data_note + ", " + std::to_string(closures) + " accepted closures");
    }
    for (const auto& [stage, samples] : stage_ms) {
        Measurement m;
        m.name = "end_to_end/stage " + stage;
        m.unit = "ms/scan";
        m.kind = FigureKind::kAbsolute;
        m.samples = samples;
        c.Add(Summarize(m), "RunState timings of stage '" + stage + "', total over the run / scans");
    }
    Measurement eval;
    eval.name = "end_to_end/evaluate+report";
    eval.unit = "ms/scan";
    eval.kind = FigureKind::kAbsolute;
    eval.samples = eval_report_ms;
    c.Add(Summarize(eval), "EvaluateRun (ground truth, PR, APE, baselines) + WriteRunReport, per scan");
    Measurement memory;
    memory.name = "end_to_end/peak memory";
    memory.unit = "MiB";
    memory.kind = FigureKind::kAbsolute;
    memory.samples = {double(PeakMemoryKb()) / 1024.0};
    c.Add(Summarize(memory), "getrusage ru_maxrss of the benchmark process after the end-to-end runs");
}

}  // namespace revisit
