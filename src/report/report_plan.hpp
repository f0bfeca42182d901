#pragma once
/// Which pages a report renders (issue 18): on a long sequence thousands of candidates reach 3 inliers, so
/// full pages go only to the closures that reached the acceptance threshold (verified in 3D, accepted or
/// not) and to the K strongest of the rest; every candidate is a row of the index's table, and
/// `revisit inspect` renders any other page on demand.
#include "report/report_input.hpp"

#include <cstddef>
#include <string>
#include <vector>

namespace revisit {

struct ReportPlan {
    std::vector<bool> closure_has_page;       ///< per entry of ReportInput::closures
    std::vector<std::size_t> closure_pages;   ///< indices with a page, ascending
    std::vector<int> map_pages;               ///< map ids with a page (maps of rendered closures), ascending
    bool MapHasPage(int map_id) const;
};

/// Which pages a report gets (ReportConfig::pages; the run's output.report_* keys).
struct ReportPagePlan {
    /// Closures that reached the threshold with a page, at most: every one when they are this many or
    /// fewer; else the worst and the best accepted and an even sample (accepted false ones besides).
    int closure_budget = 20;
    /// Candidates below the threshold with a page, strongest first (most inliers, then most votes, then earliest).
    int strongest_candidates = 8;
    bool closure_pages = true;  ///< false: no closure page at all
    bool map_pages = true;      ///< pages for the maps of the closures with a page
    /// At most this many map pages: the maps of the closures at the threshold first, then of the candidates.
    int map_budget = 30;
};

ReportPlan PlanReport(const ReportInput& input, const ReportPagePlan& pages);

/// The order in which candidates are ranked: more inliers, then more votes, then the earlier index.
bool StrongerCandidate(const ReportInput& input, std::size_t a, std::size_t b);

/// "closure #N" as an HTML link to its page when it has one, else the text with the inspect command.
std::string ClosureRef(const ReportPlan& plan, std::size_t index);
/// "map N" as an HTML link to its page when it has one, else the text.
std::string MapRef(const ReportPlan& plan, int map_id);

}  // namespace revisit
