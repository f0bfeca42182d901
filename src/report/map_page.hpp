#pragma once
/// One page per local map: its density image with ORB keypoints, its numbers, and every closure candidate
/// it takes part in (issue 8's optional per-map pages).
#include "report/pair_page.hpp"
#include "report/report_plan.hpp"

#include <filesystem>
#include <string>

namespace revisit {

/// Writes `map_NNNN.html` and its pictures into report_dir; links go to the pages `plan` renders.
/// `nav_html` is put at the top.
WrittenPage WriteMapPage(const ReportInput& input, int map_id, const std::filesystem::path& report_dir,
                         const ReportConfig& config, const ReportPlan& plan, const std::string& nav_html);

}  // namespace revisit
