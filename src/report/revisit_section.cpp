#include "report/revisit_section.hpp"

namespace revisit {

void AddRevisitSection(HtmlPage& index, const ReportInput& input) {
    if (!input.revisits) return;
    const RevisitFindings& findings = *input.revisits;
    index.Heading("Were the revisits found?", 2, "revisits");
    if (!input.evaluation_scope.empty()) index.Paragraph(input.evaluation_scope);
    if (!findings.lines.empty()) index.List(findings.lines);
    index.Paragraph("Recall and revisit coverage count different things. Recall (Metrics) counts scan pairs: of the pairs "
                    "of scans the reference says overlap, the share an accepted closure predicts, and one closure between "
                    "two local maps predicts only their scans within tau_d of each other. Revisit coverage counts places: "
                    "of the scans that come back to where the run passed before, the share in a map joined to that place "
                    "by a true closure. One true closure per revisit covers the revisit whole while recall stays low.");
    if (!findings.funnel.rows.empty()) {
        index.Paragraph("Recall as a funnel: of the map pairs that the reference poses say overlap, how many each way of "
                        "finding closures carried to each stage (the proximity pass registers the pairs the corrected poses "
                        "lay over each other: it has no votes or RANSAC).");
        index.Table(findings.funnel.header, findings.funnel.rows);
    }
    if (!findings.per_stage.rows.empty()) {
        index.Paragraph("Map pairs that the reference poses say overlap but no true accepted closure joined, by the "
                        "stage that lost them:");
        index.Table(findings.per_stage.header, findings.per_stage.rows);
    }
    if (!findings.missed.rows.empty()) index.Table(findings.missed.header, findings.missed.rows);
}

}  // namespace revisit
