#pragma once
/// Output safety: nothing a user already has is overwritten unless they ask with --force.
#include <filesystem>

namespace revisit {

/// Creates `folder` (and parents). Throws DatasetError if it exists and is not empty, unless `force`.
void PrepareOutputFolder(const std::filesystem::path& folder, bool force);

/// Throws DatasetError when writing `output` could destroy `input`: the same file or folder (also
/// through symbolic or hard links), or a folder that contains the input.
void RefuseOutputOverInput(const std::filesystem::path& input, const std::filesystem::path& output);

/// RefuseOutputOverInput, and also an output folder inside an input folder (which would add files to
/// the input: the next reading of it sees them), resolved through links; `output` need not exist yet.
void RefuseOutputInOrOverInput(const std::filesystem::path& input, const std::filesystem::path& output);

/// Creates the parent folder of `file`. Throws DatasetError if the file exists, unless `force`.
void PrepareOutputFile(const std::filesystem::path& file, bool force);

}  // namespace revisit
