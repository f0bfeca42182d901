#pragma once
/// The report index's tables (issue 18): the counts at a glance, the closures ranked by ground-truth error,
/// and one row per closure candidate and per local map, whatever their number.
#include "report/html_page.hpp"
#include "report/report_plan.hpp"

#include <string>
#include <utility>
#include <vector>

namespace revisit {

/// "accepted", "graph-rejected" (passed 3D verification, then rejected by the pose graph), "verification
/// failed" or "below threshold" (never verified).
std::string ClosureStatus(const ClosureEntry& entry);

/// What a closure rests on, for labels: "44 inliers" (detector) or "proximity pass" (registered, no image matching).
std::string ClosureEvidence(const ClosureEntry& entry);

/// The counts per source, each number once: the detector's candidates, refined, verified and accepted; the
/// proximity pass's registered and accepted; true/false when known; pages.
std::vector<std::pair<std::string, std::string>> GlanceCounts(const ReportInput& input, const ReportPlan& plan);

/// The accepted closures with a ground-truth error, worst first: all of them when at most 2 * `count`, else
/// the `count` worst and the `count` best. Writes a note instead when there are none.
void AddErrorRanking(HtmlPage& page, const ReportInput& input, const ReportPlan& plan, std::size_t count);

/// One sortable row per closure candidate.
void AddCandidateTable(HtmlPage& page, const ReportInput& input, const ReportPlan& plan);

/// One sortable row per local map.
void AddMapTable(HtmlPage& page, const ReportInput& input, const ReportPlan& plan);

}  // namespace revisit
