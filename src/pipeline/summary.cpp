#include "pipeline/summary.hpp"

#include <cmath>
#include <iomanip>
#include <sstream>

#include "settings/scene_scale_watch.hpp"

namespace revisit {

namespace {
constexpr double kApeResolution = 0.01;         ///< [m] the summary prints APE in centimetres
constexpr double kApeUnchangedFraction = 0.005;  ///< relative changes below this are noise

/// Truth of the accepted closures, revisit coverage and where the missed revisits were lost.
void PrintVerification(std::ostream& out, const RunEvaluation& e) {
    out << "  accepted closures: " << e.truth.num_true << " true / " << e.truth.num_false << " false";
    if (e.proximity_true + e.proximity_false > 0)
        out << " (of them from the proximity pass: " << e.proximity_true << " true / " << e.proximity_false << " false)";
    out << '\n';
    out << "  revisit coverage:  " << std::setprecision(0) << 100.0 * e.coverage.coverage << "% (" << e.coverage.covered_scans
        << " of " << e.coverage.revisit_scans << " revisiting scans in a map joined by a true closure)";
    if (e.proximity_true + e.proximity_false > 0) {
        out << "; by the detector alone " << 100.0 * e.detector_coverage.coverage << "% (" << e.detector_coverage.covered_scans << ")";
    }
    out << '\n';
    out << "  overlapping map pairs: " << e.missed.overlapping_pairs << ", found " << e.missed.found_pairs;
    for (const auto& [stage, count] : e.missed.per_stage) out << "; " << MissStageName(stage) << ": " << count;
    out << '\n';
    if (e.missed.overlapping_pairs > 0) {
        const RecallFunnel& d = e.missed.detector;
        const RecallFunnel& p = e.missed.proximity;
        out << "  recall funnel (map pairs): detector " << d.compared << " voted for, " << d.enough_matches << " enough matches, "
            << d.ransac << " RANSAC, " << d.refined << " refined, " << d.accepted << " accepted true; proximity pass "
            << p.compared << " registered, " << p.refined << " refined, " << p.accepted << " accepted true\n";
    }
    out << std::setprecision(1);
}

}  // namespace

std::string DescribeApeChange(double before_m, double after_m, bool reference_is_input) {
    std::ostringstream text;
    text << std::fixed << std::setprecision(2) << before_m << " m -> " << after_m << " m (";
    if (reference_is_input) {
        // Not an error against an independent reference: how far the closures moved the input poses.
        text << "reference = input poses: the closures moved the trajectory this far from them)";
        return text.str();
    }
    const double change_m = after_m - before_m;
    if (std::abs(change_m) < kApeResolution || std::abs(change_m) < kApeUnchangedFraction * before_m) {
        text << "unchanged)";
    } else if (before_m < kApeResolution) {
        text << (change_m > 0 ? "+" : "") << change_m << " m" << (change_m > 0 ? ": the closures made it worse)" : ")");
    } else {
        const double percent = 100.0 * change_m / before_m;
        text << std::setprecision(0) << std::abs(percent)
             << (percent < 0.0 ? "% lower)" : "% higher: the closures made it worse)");
    }
    return text.str();
}

void PrintRunSummary(std::ostream& out, const RunState& state, const std::optional<RunEvaluation>& evaluation,
                     const PostRunSeconds& after_chain) {
    std::size_t density = 0, refined = 0, verified = 0, accepted = 0;
    std::size_t proximity = 0, proximity_verified = 0, proximity_accepted = 0;
    for (const auto& c : state.closures) {
        if (c.method == "proximity") {
            ++proximity;
            proximity_verified += c.refinement.accepted;
            proximity_accepted += c.accepted;
            continue;
        }
        density += c.method == "density";
        refined += c.refined;
        verified += c.refined && c.refinement.accepted;
        accepted += c.accepted;
    }
    out << std::fixed << std::setprecision(1);
    out << "\n  scans             " << state.odometry.size() << (state.complete ? "" : "  (interrupted)") << '\n'
        << "  local maps        " << state.maps.size() << '\n'
        << "  closures          " << density << " detected (>= 3 inliers), " << refined << " refined in 3D, " << verified
        << " verified, " << accepted << " accepted by the pose graph\n";
    if (proximity > 0) {
        out << "  proximity pass    " << proximity << " map pairs the corrected poses (or the odometry) overlay registered, " << proximity_verified
            << " verified, " << proximity_accepted << " accepted\n";
    }
    out
        << "  wall time         " << state.wall_seconds + after_chain.evaluation.value_or(0.0) + after_chain.report.value_or(0.0)
        << " s: chain " << state.wall_seconds << " s ("
        << (state.wall_seconds > 0 ? state.odometry.size() / state.wall_seconds : 0.0) << " scans/s)";
    if (after_chain.evaluation) out << ", evaluation " << *after_chain.evaluation << " s";
    if (after_chain.report) out << ", report " << *after_chain.report << " s";
    out << "; peak memory of the chain " << state.peak_rss_kb / 1024 << " MiB\n";
    if (after_chain.chain_cpu && !state.odometry.empty()) {
        // Per scan, the evaluation's share includes what the chain made of each scan for it (evaluation.pass).
        const double scans = static_cast<double>(state.odometry.size());
        const auto pass = state.timings.find("evaluation.pass");
        const double pass_s = pass == state.timings.end() ? 0.0 : pass->second.total_ms / 1000.0;
        out << "  CPU time          chain " << *after_chain.chain_cpu << " s (" << std::setprecision(2)
            << 1e3 * *after_chain.chain_cpu / scans << " ms per scan)";
        if (after_chain.evaluation_cpu) {
            out << ", evaluation " << std::setprecision(1) << *after_chain.evaluation_cpu << " s after it + " << pass_s
                << " s in it (" << std::setprecision(2) << 1e3 * (*after_chain.evaluation_cpu + pass_s) / scans << " ms per scan)";
        }
        if (after_chain.report_cpu) out << ", report " << std::setprecision(1) << *after_chain.report_cpu << " s";
        out << std::setprecision(1) << '\n';
    }
    if (!state.odometry_fallbacks.empty()) {
        out << "  odometry          DIVERGED or degenerate on " << state.odometry_fallbacks.size() << " of " << state.odometry.size()
            << " scans (first at scan " << state.odometry_fallbacks.front()
            << "): their poses are motion predictions, marked in the report\n";
    }
    for (const auto& update : state.setting_updates) out << "  setting           " << DescribeUpdate(update) << '\n';
    out << '\n';
    out << "  stage                           total [s]    mean [ms]    calls\n";
    for (const auto& [stage, timer] : state.timings) {
        if (timer.count == 0) continue;
        out << "  " << std::left << std::setw(30) << stage << std::right << std::setw(11) << std::setprecision(2)
            << timer.total_ms / 1000.0 << std::setw(13) << std::setprecision(3) << timer.total_ms / timer.count << std::setw(9)
            << timer.count << '\n';
    }
    if (!evaluation) {
        out << "\n  (no reference poses: no metrics; give --gt FILE to evaluate)\n";
        return;
    }
    const bool partial = evaluation->reference_scans < state.odometry.size();
    if (partial) {
        out << "\n  reference poses for " << evaluation->reference_scans << " of " << state.odometry.size()
            << " scans: trajectory metrics on those only\n";
    }
    if (!evaluation->closure_metrics) {
        out << "  no local map lies wholly within the reference: no closure metrics\n";
        out << "\n  APE translation RMSE: "
            << DescribeApeChange(evaluation->odometry.ape.errors.translation_stats.rmse, evaluation->corrected.ape.errors.translation_stats.rmse,
                                 ReferenceIsInput(state))
            << '\n';
        return;
    }
    if (partial) {
        out << "  closure metrics on " << evaluation->evaluated_scans << " of " << state.odometry.size() << " scans: the "
            << evaluation->evaluated_maps << " of " << state.maps.size() << " local maps the reference covers whole\n"
            << "  " << evaluation->left_out_closures << " closure candidates (" << evaluation->left_out_accepted
            << " accepted) involve scans without a reference pose: left out\n";
    }
    out << "\n  ground truth: " << evaluation->gt_scan_pairs << " scan pairs in " << evaluation->gt_closing_segment_pairs
        << " closing segment pairs\n";
    if (evaluation->gt_scan_pairs > 0) {
        // The ground truth counts overlapping scans, the prediction pairs closer than tau_d: say how
        // much recall the protocol leaves to a map-level method at all.
        out << "  recall ceiling: " << std::setprecision(3) << evaluation->recall_ceiling() << " ("
            << evaluation->gt_pairs_within_tau << " of them lie within tau_d = " << std::defaultfloat
            << evaluation->tau_d << std::fixed << " m, the most a map closure can predict)\n";
        if (evaluation->tau_d_source == "overlap")
            out << "  tau_d from the data: revisit segment pairs closer than that mostly overlap by more than half\n";
        else if (evaluation->tau_d_source == "paper")
            out << "  tau_d is the paper's: no distance separates overlapping revisit segment pairs from the others\n";
    }
    out << '\n';
    out << "  method            precision  recall     F1   R@100%P   APE before [m]  APE after [m]\n";
    for (const auto& m : evaluation->methods) {
        out << "  " << std::left << std::setw(16) << m.method << std::right << std::setprecision(3) << std::setw(11)
            << m.best.precision << std::setw(8) << m.best.recall << std::setw(7) << m.best.f1 << std::setw(10);
        if (m.has_full_precision) out << m.recall_at_full_precision;
        else out << "-";
        out << std::setprecision(2) << std::setw(17);
        if (m.ape_rmse_before) out << *m.ape_rmse_before; else out << "-";
        out << std::setw(15);
        if (m.ape_rmse_after) out << *m.ape_rmse_after; else out << "-";
        out << '\n';
    }
    const auto& before = evaluation->odometry.ape.errors.translation_stats;
    const auto& after = evaluation->corrected.ape.errors.translation_stats;
    if (before.rmse > 0 || after.rmse > 0)
        out << "\n  APE translation RMSE: " << DescribeApeChange(before.rmse, after.rmse, ReferenceIsInput(state)) << '\n';
    PrintVerification(out, *evaluation);
}

}  // namespace revisit
