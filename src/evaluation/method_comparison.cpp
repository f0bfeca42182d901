#include "evaluation/method_comparison.hpp"

#include <iomanip>
#include <ostream>
#include <sstream>

namespace revisit {
namespace {

std::string Fixed(double value, int digits) {
    std::ostringstream text;
    text << std::fixed << std::setprecision(digits) << value;
    return text.str();
}

std::string OptionalFixed(const std::optional<double>& value, int digits) {
    return value ? Fixed(*value, digits) : std::string("-");
}

}  // namespace

PrSweepResult ScoreMapClosures(const std::vector<MapClosureForEval>& closures, const Poses& T_odom_sensor,
                               const std::vector<ScanPair>& ground_truth, const PredictedClosureConfig& config,
                               int min_inliers) {
    const std::vector<ScoredPair> predicted = ExpandMapClosures(closures, T_odom_sensor, config);
    return SweepPrecisionRecall(predicted, ground_truth, InlierThresholds(predicted, min_inliers),
                                Acceptance::kScoreAtLeast);
}

PrSweepResult ScoreScanContext(const std::vector<ScanContextCandidate>& candidates,
                               const std::vector<ScanPair>& ground_truth, const ScanContextSweepConfig& config) {
    return SweepPrecisionRecall(ScanContextPairs(candidates), ground_truth,
                                RangeThresholds(config.first, config.last, config.step), Acceptance::kScoreAtMost);
}

MethodSummary SummarizeMethod(const std::string& method, const PrSweepResult& sweep) {
    MethodSummary summary;
    summary.method = method;
    summary.best = sweep.best;
    summary.has_full_precision = sweep.has_full_precision;
    summary.recall_at_full_precision = sweep.recall_at_full_precision;
    return summary;
}

void WritePrCurveCsv(std::ostream& out, const PrSweepResult& sweep) {
    out << "threshold,predicted,true_positives,ground_truth,precision,recall,f1\n";
    out << std::setprecision(10);
    for (const auto& p : sweep.curve)
        out << p.threshold << ',' << p.num_predicted << ',' << p.true_positives << ',' << p.num_ground_truth << ','
            << p.precision << ',' << p.recall << ',' << p.f1 << '\n';
}

void WriteComparisonTable(std::ostream& out, const std::vector<MethodSummary>& methods) {
    out << "| method | P | R | F1 | threshold | R@100%P | APE before [m] | APE after [m] |\n";
    out << "|---|---|---|---|---|---|---|---|\n";
    for (const auto& m : methods) {
        out << "| " << m.method << " | " << Fixed(m.best.precision, 3) << " | " << Fixed(m.best.recall, 3) << " | "
            << Fixed(m.best.f1, 3) << " | " << Fixed(m.best.threshold, 2) << " | "
            << (m.has_full_precision ? Fixed(m.recall_at_full_precision, 3) : std::string("-")) << " | "
            << OptionalFixed(m.ape_rmse_before, 2) << " | " << OptionalFixed(m.ape_rmse_after, 2) << " |\n";
    }
}

}  // namespace revisit
