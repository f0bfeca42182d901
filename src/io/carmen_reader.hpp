#pragma once
/// CARMEN logs (.log, .clf; plain, gzip or bzip2): one scan per laser line of one laser (FLASER by
/// default, else the first laser kind in the file; ReaderOptions::sensor_label picks FLASER, RLASER
/// or ROBOTLASER1), its laser pose as the odometry prior. docs/formats.md describes the details.
#include <filesystem>
#include <memory>

#include "io/reader.hpp"

namespace revisit {

/// `.log`, `.clf`, optionally followed by `.gz` or `.bz2`.
bool HasCarmenExtension(const std::filesystem::path& path);

/// Reads the log once to check every line and find the scans, their maximum range and whether they
/// have times, then streams. Throws DatasetError (file and line) for a file that is not a CARMEN log
/// or a damaged line.
std::unique_ptr<Reader> OpenCarmenLog(const std::filesystem::path& path, const ReaderOptions& options);

}  // namespace revisit
