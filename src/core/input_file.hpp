#pragma once
/// Opening a file for reading with a message that names it and says what is wrong (a folder where a
/// file should be, a missing file), instead of a stream error from deep inside a parser.
#include <filesystem>
#include <fstream>

namespace revisit {

/// Throws DatasetError naming `file` when it is missing, not a regular file, or cannot be opened.
std::ifstream OpenForReading(const std::filesystem::path& file, std::ios::openmode mode = std::ios::in);

}  // namespace revisit
