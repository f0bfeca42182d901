#include "report/index_tables.hpp"

#include "report/pair_page.hpp"
#include "report/svg_plot.hpp"

#include <algorithm>

namespace revisit {
namespace {

std::string Cell(const std::string& html) { return "<td>" + html + "</td>"; }
std::string TextCell(const std::string& text) { return Cell(EscapeXml(text)); }

std::string Scans(const ScanRange& range) { return std::to_string(range.first) + "-" + std::to_string(range.last); }

std::string ErrorText(const ClosureEntry& entry) {
    return entry.gt_translation_error ? FormatNumber(*entry.gt_translation_error, 2) : "-";
}

std::string Count(std::size_t n) { return std::to_string(n); }

}  // namespace

std::string ClosureStatus(const ClosureEntry& entry) {
    if (entry.accepted) return "accepted";
    if (entry.verified) return "graph-rejected";
    if (entry.reached_threshold) return "verification failed";
    return "below threshold";
}

std::string ClosureEvidence(const ClosureEntry& entry) {
    return entry.proximity ? std::string("proximity pass") : std::to_string(entry.closure.num_inliers) + " inliers";
}

std::vector<std::pair<std::string, std::string>> GlanceCounts(const ReportInput& input, const ReportPlan& plan) {
    std::size_t candidates = 0, refined = 0, verified = 0, accepted = 0, proximity_accepted = 0;
    for (const auto& entry : input.closures) {
        if (entry.proximity) {
            proximity_accepted += entry.accepted;
            continue;
        }
        ++candidates;
        refined += entry.reached_threshold || entry.accepted;
        verified += entry.verified || entry.accepted;
        accepted += entry.accepted;
    }
    std::vector<std::pair<std::string, std::string>> rows{
        {"detector: candidates (>= 3 inliers)", Count(candidates)},
        {"detector: reached the acceptance threshold, registered in 3D", Count(refined)},
        {"detector: passed 3D verification", Count(verified)},
        {"detector: accepted into the pose graph", Count(accepted)}};
    if (input.proximity_registered > 0) {
        rows.push_back({"proximity pass: map pairs registered (from the corrected poses)", Count(input.proximity_registered)});
        rows.push_back({"proximity pass: accepted into the pose graph", Count(proximity_accepted)});
    }
    if (input.true_closures && input.false_closures)
        rows.push_back({"accepted closures against the reference: true / false",
                        std::to_string(*input.true_closures) + " / " + std::to_string(*input.false_closures)});
    rows.push_back({"closure pages in this report", Count(plan.closure_pages.size()) + " of " + Count(input.closures.size()) +
                                                        " (the rest: table below, `revisit inspect`)"});
    return rows;
}

void AddErrorRanking(HtmlPage& page, const ReportInput& input, const ReportPlan& plan, std::size_t count) {
    std::vector<std::size_t> ranked;
    for (std::size_t i = 0; i < input.closures.size(); ++i)
        if (input.closures[i].accepted && input.closures[i].gt_translation_error) ranked.push_back(i);
    if (ranked.empty()) {
        page.Paragraph("No accepted closure with a ground-truth error (no reference, or no closure accepted).");
        return;
    }
    std::stable_sort(ranked.begin(), ranked.end(), [&](std::size_t a, std::size_t b) {
        return *input.closures[a].gt_translation_error > *input.closures[b].gt_translation_error;
    });
    std::vector<std::string> rows;
    const auto row = [&](std::size_t i, const std::string& rank) {
        const auto& entry = input.closures[i];
        const Closure& c = entry.closure;
        rows.push_back("<tr>" + TextCell(rank) + Cell(ClosureRef(plan, i)) +
                       Cell(MapRef(plan, c.query_id) + " to " + MapRef(plan, c.ref_id)) + TextCell(Count(c.num_inliers)) +
                       TextCell(ErrorText(entry)) +
                       TextCell(entry.gt_rotation_error ? FormatNumber(*entry.gt_rotation_error, 2) : "-") + "</tr>\n");
    };
    if (ranked.size() <= 2 * count) {
        for (std::size_t r = 0; r < ranked.size(); ++r) row(ranked[r], std::to_string(r + 1) + " of " + Count(ranked.size()));
    } else {
        for (std::size_t r = 0; r < count; ++r) row(ranked[r], "worst " + std::to_string(r + 1));
        rows.push_back("<tr><td colspan=\"6\">... " + Count(ranked.size() - 2 * count) + " more ...</td></tr>\n");
        for (std::size_t r = ranked.size() - count; r < ranked.size(); ++r)
            row(ranked[r], "best " + std::to_string(ranked.size() - r));
    }
    page.Raw("<table>\n<tr><th>rank (worst first)</th><th>closure</th><th>maps</th><th>inliers</th>"
             "<th>error [m]</th><th>yaw error [deg]</th></tr>\n");
    for (const auto& r : rows) page.Raw(r);
    page.Raw("</table>\n");
}

void AddCandidateTable(HtmlPage& page, const ReportInput& input, const ReportPlan& plan) {
    std::vector<std::string> rows;
    rows.reserve(input.closures.size());
    for (std::size_t i = 0; i < input.closures.size(); ++i) {
        const auto& entry = input.closures[i];
        const Closure& c = entry.closure;
        const std::string status = ClosureStatus(entry);
        const std::string page_cell = plan.closure_has_page[i]
                                          ? HtmlLink(ClosureStem(i) + ".html", "page")
                                          : "<code>" + EscapeXml(std::string(kInspectCommand) + " --closure " + std::to_string(i)) + "</code>";
        std::string css = status;
        std::replace(css.begin(), css.end(), ' ', '-');
        rows.push_back("<tr class=\"status-" + css + "\">" + TextCell(std::to_string(i)) + Cell(MapRef(plan, c.query_id)) +
                       Cell(MapRef(plan, c.ref_id)) + TextCell(Scans(c.query_scans)) + TextCell(Scans(c.ref_scans)) +
                       TextCell(entry.proximity ? "-" : Count(c.num_inliers)) + TextCell(entry.proximity ? "-" : Count(c.num_votes)) +
                       TextCell(status) + TextCell(entry.proximity ? "proximity pass; " + entry.reason : entry.reason) +
                       TextCell(ErrorText(entry)) + Cell(page_cell) + "</tr>\n");
    }
    page.SortableTable({"#", "query map", "reference map", "query scans", "reference scans", "inliers", "votes", "status",
                        "why", "GT error [m]", "page"},
                       rows, "candidates");
}

void AddMapTable(HtmlPage& page, const ReportInput& input, const ReportPlan& plan) {
    std::vector<std::size_t> candidates(input.map_ids.size(), 0);
    std::vector<std::size_t> accepted(input.map_ids.size(), 0);
    const auto slot = [&](int id) {
        const auto it = std::find(input.map_ids.begin(), input.map_ids.end(), id);
        return it == input.map_ids.end() ? input.map_ids.size() : std::size_t(it - input.map_ids.begin());
    };
    // Map ids are usually 0..n-1 in order; the search is only the fallback.
    const auto index_of = [&](int id) {
        const std::size_t i = static_cast<std::size_t>(id);
        return id >= 0 && i < input.map_ids.size() && input.map_ids[i] == id ? i : slot(id);
    };
    for (const auto& entry : input.closures)
        for (const int id : {entry.closure.query_id, entry.closure.ref_id})
            if (const std::size_t i = index_of(id); i < input.map_ids.size()) {
                ++candidates[i];
                accepted[i] += entry.accepted;
            }
    std::vector<std::string> rows;
    rows.reserve(input.map_ids.size());
    for (std::size_t i = 0; i < input.map_ids.size(); ++i) {
        const int id = input.map_ids[i];
        const std::string page_cell = plan.MapHasPage(id)
                                          ? HtmlLink(MapStem(id) + ".html", "page")
                                          : "<code>" + EscapeXml(std::string(kInspectCommand) + " --map " + std::to_string(id)) + "</code>";
        rows.push_back("<tr>" + TextCell(std::to_string(id)) +
                       TextCell(i < input.map_scans.size() ? Scans(input.map_scans[i]) : "-") + TextCell(Count(candidates[i])) +
                       TextCell(Count(accepted[i])) + Cell(page_cell) + "</tr>\n");
    }
    page.SortableTable({"map", "scans", "candidates", "accepted closures", "page"}, rows, "maps-table");
}

}  // namespace revisit
