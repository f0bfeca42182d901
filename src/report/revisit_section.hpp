#pragma once
/// The report index's "Were the revisits found?" section: truth of the accepted closures, revisit
/// coverage, and the stage that lost each revisit no true closure found (issue 16).
#include "report/html_page.hpp"
#include "report/report_input.hpp"

namespace revisit {

/// Adds the section when `input.revisits` holds findings (runs with reference poses); nothing otherwise.
void AddRevisitSection(HtmlPage& index, const ReportInput& input);

}  // namespace revisit
