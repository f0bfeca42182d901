/// The report's pages do not grow with the sequence: a bounded set of closure pages chosen to show the
/// worst, the best, a sample and every false closure.
#include <gtest/gtest.h>

#include <set>

#include "report/report_plan.hpp"

namespace revisit {
namespace {

/// `n` closures that reached the threshold, accepted, with reference errors 0.01 * k, and `weak` below it.
ReportInput ManyClosures(int n, int weak) {
    ReportInput input;
    for (int k = 0; k < n; ++k) {
        ClosureEntry entry;
        entry.closure.query_id = 2 * k + 1;
        entry.closure.ref_id = 2 * k;
        entry.closure.num_inliers = 20 + k % 7;
        entry.accepted = entry.reached_threshold = entry.verified = true;
        entry.gt_translation_error = 0.01 * ((k * 37) % n);  // errors in a shuffled order
        input.closures.push_back(entry);
    }
    for (int k = 0; k < weak; ++k) {
        ClosureEntry entry;
        entry.closure.num_inliers = 3 + k % 5;
        input.closures.push_back(entry);
    }
    return input;
}

std::set<std::size_t> Pages(const ReportPlan& plan) { return {plan.closure_pages.begin(), plan.closure_pages.end()}; }

TEST(PlanReport, FewClosuresAllGetPages) {
    const ReportInput input = ManyClosures(10, 0);
    EXPECT_EQ(PlanReport(input, ReportPagePlan{24, 20, true, true, 30}).closure_pages.size(), 10u);
}

TEST(PlanReport, ManyClosuresGetTheBudgetWithTheWorstTheBestAndEveryFalseOne) {
    for (const int n : {100, 1000, 10000}) {
        ReportInput input = ManyClosures(n, 3 * n);
        input.closures[n / 2].judged_false = true;
        input.closures[n / 2 + 1].judged_false = true;
        const ReportPlan plan = PlanReport(input, ReportPagePlan{24, 20, true, true, 30});
        const auto pages = Pages(plan);
        // The same size at any length: the budget, the false ones, the strongest weak candidates.
        EXPECT_EQ(pages.size(), 24u + 2u + 20u) << n;
        EXPECT_TRUE(pages.count(std::size_t(n / 2)) && pages.count(std::size_t(n / 2 + 1))) << "every false closure";
        // The worst eight (largest reference error) and the best four are among them.
        std::vector<std::pair<double, std::size_t>> ranked;
        for (int k = 0; k < n; ++k)
            if (!input.closures[std::size_t(k)].judged_false) ranked.push_back({*input.closures[std::size_t(k)].gt_translation_error, std::size_t(k)});
        std::sort(ranked.begin(), ranked.end());
        for (std::size_t r = 0; r < 8; ++r) EXPECT_TRUE(pages.count(ranked[ranked.size() - 1 - r].second)) << "worst " << r;
        for (std::size_t r = 0; r < 4; ++r) EXPECT_TRUE(pages.count(ranked[r].second)) << "best " << r;
        // The sample spreads over the whole run: a page in each quarter of the closures found.
        for (int quarter = 0; quarter < 4; ++quarter) {
            int in_quarter = 0;
            for (const std::size_t i : pages) in_quarter += int(i) >= quarter * n / 4 && int(i) < (quarter + 1) * n / 4;
            EXPECT_GE(in_quarter, 2) << n << " quarter " << quarter;
        }
        // Map pages: at most the budget, maps of the closures with a page, those at the threshold first.
        EXPECT_EQ(plan.map_pages.size(), 30u);
        for (const int id : plan.map_pages) {
            bool of_a_page = false;
            for (const std::size_t i : pages) {
                const bool at_threshold = input.closures[i].accepted || input.closures[i].reached_threshold;
                of_a_page |= at_threshold && (input.closures[i].closure.query_id == id || input.closures[i].closure.ref_id == id);
            }
            EXPECT_TRUE(of_a_page) << "map " << id;
        }
    }
}

}  // namespace
}  // namespace revisit
