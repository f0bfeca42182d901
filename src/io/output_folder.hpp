#pragma once
/// Output safety: nothing a user already has is overwritten unless they ask with --force.
#include <filesystem>

namespace revisit {

/// Creates `folder` (and parents). Throws DatasetError if it exists and is not empty, unless `force`.
void PrepareOutputFolder(const std::filesystem::path& folder, bool force);

/// Creates the parent folder of `file`. Throws DatasetError if the file exists, unless `force`.
void PrepareOutputFile(const std::filesystem::path& file, bool force);

}  // namespace revisit
