#include "pipeline/run_and_report.hpp"

#include "core/cpu_time.hpp"

#include "pipeline/evaluate.hpp"
#include "pipeline/interrupt.hpp"
#include "pipeline/report_builder.hpp"
#include "pipeline/summary.hpp"
#include "core/allocator.hpp"
#include "runfolder/run_files.hpp"

#include <chrono>

namespace revisit {
namespace {

/// Keeps what PrintRunSummary and the callers read (counts, verdicts, timings, the odometry's length).
void ReleaseForSummary(RunState& state) {
    for (auto& record : state.closures) {
        std::vector<FeatureMatch>().swap(record.closure.matches);
        std::vector<std::uint8_t>().swap(record.closure.inlier_mask);
        std::vector<Eigen::Vector2f>().swap(record.closure.query_keypoints);
        std::vector<Eigen::Vector2f>().swap(record.closure.ref_keypoints);
    }
    std::vector<MapComparison>().swap(state.comparisons);
    Poses().swap(state.corrected);
    Poses().swap(state.reference);
    ReleaseFreeMemory();
}

}  // namespace

RunState RunAndReport(const RunOptions& options, const PipelineConfig& config, std::ostream& log, std::ostream& out) {
    std::unique_ptr<EvaluationPass> chain_pass;  // the evaluation's share of each scan, made by the chain
    RunState state = RunPipeline(options, config, log, &chain_pass);
    const RunFolder run(options.out);
    std::optional<RunEvaluation> evaluation;
    PostRunSeconds after_chain;
    after_chain.chain_cpu = ProcessCpuSeconds();
    bool report_written = false;
    if (state.complete) {
        const auto start = std::chrono::steady_clock::now();
        // The evaluation reads its own copy of the state: on a long run the chain's would otherwise stay
        // beside it, the process's peak of memory.
        ReleaseForSummary(state);
        // From the run folder as written, as `revisit eval` reads it: the poses' files hold 9 decimals,
        // so the metrics (and the ground truth's cache key) are the ones a later eval recomputes.
        evaluation = EvaluateRun(run, ReadRunState(run, false), options, config, log, chain_pass.get());
        after_chain.evaluation = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        chain_pass.reset();  // its scratch files go before the report
        after_chain.evaluation_cpu = ProcessCpuSeconds() - *after_chain.chain_cpu;
        // Ctrl-C after the chain: the run folder is complete; the report is skipped (an earlier one stays).
        if (config.output.write_report && !InterruptRequested()) {
            try {
                const double report_start = ProcessCpuSeconds();
                after_chain.report = WriteRunReport(run, log, {options.quiet, {}});
                after_chain.report_cpu = ProcessCpuSeconds() - report_start;
                report_written = true;
            } catch (const Interrupted&) {
            }
        }
        if (InterruptRequested() && !report_written) {
            log << "interrupted during the evaluation or the report: the run folder is complete, the report was skipped; "
                   "write it with `revisit report "
                << run.root().string() << "`\n";
        }
    } else {
        log << "skipped evaluation and report; finish them with `revisit eval " << run.root().string()
            << "` and `revisit report " << run.root().string() << "`\n";
    }
    PrintRunSummary(out, state, evaluation, after_chain);
    out << "\nrun folder: " << run.root().string() << '\n';
    if (report_written) out << "report:     " << run.report_index().string() << '\n';
    else if (config.output.write_report) out << "report:     skipped (interrupted); `revisit report " << run.root().string() << "` writes it\n";
    return state;
}

}  // namespace revisit
