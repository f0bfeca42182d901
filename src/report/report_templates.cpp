#include "report/report_templates.hpp"

#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>

#ifndef REVISIT_SHARE_DIR_DEFAULT
#define REVISIT_SHARE_DIR_DEFAULT ""
#endif

namespace revisit {
namespace fs = std::filesystem;

namespace {

/// The running executable's folder (Linux), empty when unknown.
fs::path ExecutableDir() {
    std::error_code error;
    const fs::path exe = fs::read_symlink("/proc/self/exe", error);
    return error ? fs::path() : exe.parent_path();
}

std::string ReadTemplate(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    if (!in) throw std::runtime_error("report: cannot read template " + file.string());
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

}  // namespace

fs::path FindShareDir() {
    if (const char* env = std::getenv("REVISIT_SHARE_DIR"); env && *env) {
        if (!fs::is_directory(fs::path(env) / "report"))
            throw std::runtime_error("report: REVISIT_SHARE_DIR=" + std::string(env) + " has no report/ folder of templates");
        return env;
    }
    std::vector<fs::path> candidates;
    if (const fs::path exe_dir = ExecutableDir(); !exe_dir.empty()) candidates.push_back(exe_dir.parent_path() / "share" / "revisit");
    if (*REVISIT_SHARE_DIR_DEFAULT) candidates.emplace_back(REVISIT_SHARE_DIR_DEFAULT);
    std::string tried;
    for (const auto& dir : candidates) {
        if (fs::is_directory(dir / "report")) return dir;
        tried += (tried.empty() ? "" : ", ") + (dir / "report").string();
    }
    throw std::runtime_error("report: templates not found (tried " + tried +
                             "); set REVISIT_SHARE_DIR to the folder holding report/page.html");
}

ReportTemplates LoadReportTemplates(const fs::path& share_dir) {
    ReportTemplates templates;
    templates.dir = share_dir / "report";
    templates.page = ReadTemplate(templates.dir / "page.html");
    templates.style = ReadTemplate(templates.dir / "style.css");
    templates.table_script = ReadTemplate(templates.dir / "table.js");
    for (const char* field : {"{{title}}", "{{style}}", "{{body}}"})
        if (templates.page.find(field) == std::string::npos)
            throw std::runtime_error("report: template " + (templates.dir / "page.html").string() + " lacks " + field);
    return templates;
}

const ReportTemplates& DefaultReportTemplates() {
    static const ReportTemplates templates = LoadReportTemplates(FindShareDir());
    return templates;
}

std::string FillTemplate(const std::string& text, const std::vector<std::pair<std::string, std::string>>& values) {
    std::string out;
    out.reserve(text.size());
    std::size_t pos = 0;
    while (pos < text.size()) {
        const std::size_t open = text.find("{{", pos);
        if (open == std::string::npos) break;
        const std::size_t close = text.find("}}", open + 2);
        if (close == std::string::npos) break;
        const std::string key = text.substr(open + 2, close - open - 2);
        out.append(text, pos, open - pos);
        bool known = false;
        for (const auto& [name, value] : values)
            if (name == key) {
                out += value;
                known = true;
                break;
            }
        if (!known) out.append(text, open, close + 2 - open);  // not ours: leave it as written
        pos = close + 2;
    }
    out.append(text, pos, std::string::npos);
    return out;
}

}  // namespace revisit
