#include "report/report_plan.hpp"

#include "report/html_page.hpp"
#include "report/pair_page.hpp"
#include "report/svg_plot.hpp"

#include <algorithm>
#include <numeric>

namespace revisit {

bool ReportPlan::MapHasPage(int map_id) const { return std::binary_search(map_pages.begin(), map_pages.end(), map_id); }

bool StrongerCandidate(const ReportInput& input, std::size_t a, std::size_t b) {
    const Closure& x = input.closures[a].closure;
    const Closure& y = input.closures[b].closure;
    if (x.num_inliers != y.num_inliers) return x.num_inliers > y.num_inliers;
    if (x.num_votes != y.num_votes) return x.num_votes > y.num_votes;
    return a < b;
}

ReportPlan PlanReport(const ReportInput& input, int strongest_candidates, bool closure_pages, bool map_pages) {
    ReportPlan plan;
    const std::size_t n = input.closures.size();
    plan.closure_has_page.assign(n, false);
    if (closure_pages) {
        std::vector<std::size_t> below;
        for (std::size_t i = 0; i < n; ++i) {
            const auto& entry = input.closures[i];
            if (entry.accepted || entry.reached_threshold) plan.closure_has_page[i] = true;
            else below.push_back(i);
        }
        const std::size_t k = std::min(below.size(), static_cast<std::size_t>(std::max(0, strongest_candidates)));
        std::partial_sort(below.begin(), below.begin() + k, below.end(),
                          [&](std::size_t a, std::size_t b) { return StrongerCandidate(input, a, b); });
        for (std::size_t j = 0; j < k; ++j) plan.closure_has_page[below[j]] = true;
        for (std::size_t i = 0; i < n; ++i)
            if (plan.closure_has_page[i]) plan.closure_pages.push_back(i);
    }
    if (map_pages) {
        for (const std::size_t i : plan.closure_pages) {
            plan.map_pages.push_back(input.closures[i].closure.query_id);
            plan.map_pages.push_back(input.closures[i].closure.ref_id);
        }
        std::sort(plan.map_pages.begin(), plan.map_pages.end());
        plan.map_pages.erase(std::unique(plan.map_pages.begin(), plan.map_pages.end()), plan.map_pages.end());
    }
    return plan;
}

std::string ClosureRef(const ReportInput& input, const ReportPlan& plan, std::size_t index) {
    const std::string text = "closure #" + std::to_string(index);
    if (index < plan.closure_has_page.size() && plan.closure_has_page[index]) return HtmlLink(ClosureStem(index) + ".html", text);
    return EscapeXml(text) + " <code>" + EscapeXml(input.inspect_command + " --closure " + std::to_string(index)) + "</code>";
}

std::string MapRef(const ReportPlan& plan, int map_id) {
    const std::string text = "map " + std::to_string(map_id);
    return plan.MapHasPage(map_id) ? HtmlLink(MapStem(map_id) + ".html", text) : EscapeXml(text);
}

}  // namespace revisit
