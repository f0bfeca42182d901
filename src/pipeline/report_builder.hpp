#pragma once
/// The report of a run, drawn from its folder alone (`revisit report` needs nothing else).
#include <ostream>

#include "pipeline/config.hpp"
#include "pipeline/run_folder.hpp"
#include "report/report_input.hpp"

namespace revisit {

/// Everything the report shows, read from the run folder; maps and density images load on demand.
ReportInput LoadReportInput(const RunFolder& run);

/// Loads the run's database.bin; throws DatasetError naming it when it is missing, corrupt or from
/// another configuration (`revisit inspect` needs its keypoints; `revisit report` only warns).
void CheckRunDatabase(const RunFolder& run);

/// Writes run/report/index.html and its pages and pictures.
void WriteRunReport(const RunFolder& run, std::ostream& log);

}  // namespace revisit
