#pragma once
/// The report of a run, drawn from its folder alone (`revisit report` needs nothing else).
#include <ostream>
#include <string>
#include <vector>

#include "config/config.hpp"
#include "runfolder/run_folder.hpp"
#include "report/report_input.hpp"
#include "report/report_writer.hpp"

namespace revisit {

/// Everything the report shows, read from the run folder; maps and density images load on demand.
ReportInput LoadReportInput(const RunFolder& run);

/// Loads the run's database.bin; throws DatasetError naming it when it is missing, corrupt or from
/// another configuration (`revisit inspect` needs its keypoints; `revisit report` only warns).
void CheckRunDatabase(const RunFolder& run);

/// The report settings of the run's own configuration (output.report_candidates), `overrides` (key=value) on top.
ReportConfig RunReportConfig(const RunFolder& run, const std::vector<std::string>& overrides = {});

struct ReportRunOptions {
    bool quiet = false;                   ///< no progress line
    std::vector<std::string> overrides;   ///< key=value over the run's config.yaml (e.g. output.report_candidates=50)
};

/// Regenerates run/report/: index.html, its pictures and the bounded set of pages (report_plan.hpp), with a
/// progress line on `log`. The new report is built beside the old one and replaces it when complete; on
/// an error or Ctrl-C (throws Interrupted) the old report stays. Returns the wall time [s].
double WriteRunReport(const RunFolder& run, std::ostream& log, const ReportRunOptions& options = {});

}  // namespace revisit
