#pragma once
/// The HTML page of a merge (`revisit merge`, `revisit run --against`): the sessions in their colours
/// (the same as sessions.svg), whether each is tied to the common frame, per-session metrics when
/// references exist, and every cross-session closure candidate with its verdict.
#include <filesystem>
#include <string>

#include "sessions/session_merge.hpp"

namespace revisit {

/// The page's HTML; it shows `sessions.svg` from the same folder.
std::string MergeReportHtml(const MergeResult& result);

/// Writes `out`/index.html (atomically).
void WriteMergeReport(const std::filesystem::path& out, const MergeResult& result);

}  // namespace revisit
