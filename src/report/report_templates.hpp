#pragma once
/// The report's look, read at run time from share/report/ (issue 18): the page skeleton, the stylesheet and the
/// table script are files a user can edit without rebuilding. Every page inlines them, so a report stays one
/// self-contained folder.
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace revisit {

struct ReportTemplates {
    std::filesystem::path dir;  ///< where they were read from
    std::string page;           ///< page.html: {{title}}, {{style}}, {{body}}
    std::string style;          ///< style.css, inlined into every page
    std::string table_script;   ///< table.js, inlined into pages with sortable tables
};

/// The folder holding report/ templates, first that exists: $REVISIT_SHARE_DIR (must exist when set), then
/// <executable>/../share/revisit (installed), then the source tree's share/ (compile-time default).
/// Throws std::runtime_error naming every path tried.
std::filesystem::path FindShareDir();

/// Reads share_dir/report/{page.html,style.css,table.js}; throws std::runtime_error naming a missing or
/// incomplete file.
ReportTemplates LoadReportTemplates(const std::filesystem::path& share_dir);

/// LoadReportTemplates(FindShareDir()), read once per process (thread-safe).
const ReportTemplates& DefaultReportTemplates();

/// `text` with every "{{key}}" replaced by its value (values are inserted verbatim, not rescanned).
std::string FillTemplate(const std::string& text, const std::vector<std::pair<std::string, std::string>>& values);

}  // namespace revisit
