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

namespace {

/// How far a closure is from right: the reference's error when known, else the registration's RMS.
double Badness(const ClosureEntry& entry) {
    if (entry.gt_translation_error) return *entry.gt_translation_error;
    return entry.rmse.value_or(0.0);
}

/// The pages of the closures that reached the threshold: all when within the budget; else every false
/// one, then the worst third and the best sixth of the accepted, then an even sample of the rest, so
/// that a sequence of any length gets a report of one size.
void ChooseReachedPages(const ReportInput& input, const std::vector<std::size_t>& reached, std::size_t budget,
                        std::vector<bool>& has_page) {
    if (reached.size() <= budget) {
        for (const std::size_t i : reached) has_page[i] = true;
        return;
    }
    std::vector<std::size_t> accepted;
    for (const std::size_t i : reached) {
        if (input.closures[i].judged_false) has_page[i] = true;
        else if (input.closures[i].accepted) accepted.push_back(i);
    }
    std::stable_sort(accepted.begin(), accepted.end(),
                     [&](std::size_t a, std::size_t b) { return Badness(input.closures[a]) > Badness(input.closures[b]); });
    const std::size_t worst = std::min(accepted.size(), budget / 3);
    const std::size_t best = std::min(accepted.size() - worst, budget / 6);
    for (std::size_t k = 0; k < worst; ++k) has_page[accepted[k]] = true;
    for (std::size_t k = 0; k < best; ++k) has_page[accepted[accepted.size() - 1 - k]] = true;
    std::vector<std::size_t> rest;
    for (const std::size_t i : reached)
        if (!has_page[i]) rest.push_back(i);
    const std::size_t sample = std::min(rest.size(), budget - worst - best);
    // Evenly over the run (reached is in the order the closures were found): the k-th of `sample` strata.
    for (std::size_t k = 0; k < sample; ++k) has_page[rest[(2 * k + 1) * rest.size() / (2 * sample)]] = true;
}

}  // namespace

ReportPlan PlanReport(const ReportInput& input, const ReportPagePlan& pages) {
    ReportPlan plan;
    const std::size_t n = input.closures.size();
    plan.closure_has_page.assign(n, false);
    if (pages.closure_pages) {
        std::vector<std::size_t> reached, below;
        for (std::size_t i = 0; i < n; ++i) {
            const auto& entry = input.closures[i];
            (entry.accepted || entry.reached_threshold ? reached : below).push_back(i);
        }
        ChooseReachedPages(input, reached, static_cast<std::size_t>(std::max(0, pages.closure_budget)), plan.closure_has_page);
        const std::size_t k = std::min(below.size(), static_cast<std::size_t>(std::max(0, pages.strongest_candidates)));
        std::partial_sort(below.begin(), below.begin() + k, below.end(),
                          [&](std::size_t a, std::size_t b) { return StrongerCandidate(input, a, b); });
        for (std::size_t j = 0; j < k; ++j) plan.closure_has_page[below[j]] = true;
        for (std::size_t i = 0; i < n; ++i)
            if (plan.closure_has_page[i]) plan.closure_pages.push_back(i);
    }
    if (pages.map_pages) {
        // The maps of the closures at the threshold first: a candidate's maps are on its own page too.
        std::vector<std::size_t> order = plan.closure_pages;
        std::stable_partition(order.begin(), order.end(), [&](std::size_t i) {
            return input.closures[i].accepted || input.closures[i].reached_threshold;
        });
        const std::size_t budget = static_cast<std::size_t>(std::max(0, pages.map_budget));
        std::vector<int> chosen;
        for (const std::size_t i : order) {
            for (const int id : {input.closures[i].closure.query_id, input.closures[i].closure.ref_id}) {
                if (chosen.size() < budget && std::find(chosen.begin(), chosen.end(), id) == chosen.end()) chosen.push_back(id);
            }
        }
        std::sort(chosen.begin(), chosen.end());
        plan.map_pages = std::move(chosen);
    }
    return plan;
}

std::string ClosureRef(const ReportPlan& plan, std::size_t index) {
    const std::string text = "closure #" + std::to_string(index);
    if (index < plan.closure_has_page.size() && plan.closure_has_page[index]) return HtmlLink(ClosureStem(index) + ".html", text);
    return EscapeXml(text) + " <code>" + EscapeXml(std::string(kInspectCommand) + " --closure " + std::to_string(index)) + "</code>";
}

std::string MapRef(const ReportPlan& plan, int map_id) {
    const std::string text = "map " + std::to_string(map_id);
    return plan.MapHasPage(map_id) ? HtmlLink(MapStem(map_id) + ".html", text) : EscapeXml(text);
}

}  // namespace revisit
