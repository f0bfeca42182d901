#pragma once
/// Persistence of the closure database (one binary file), for multi-session relocalization.
#include <filesystem>
#include <string>

#include "closures/detector.hpp"

namespace revisit {

/// Format version written by SaveDatabase; LoadDatabase refuses any other.
inline constexpr std::uint32_t kDatabaseVersion = 1;

/// Text of the configuration values that make descriptors comparable (density, features, tree);
/// a database only loads under a configuration with the same fingerprint.
std::string DatabaseFingerprint(const ClosureDetectorConfig& config);

/// Writes maps (metadata, keypoints, descriptors, density images) with a version header and checksum.
void SaveDatabase(const ClosureDetector& detector, const std::filesystem::path& file);

/// Reads a database written by SaveDatabase and starts a new session, so that maps added afterwards
/// are matched against every stored map. Throws DatasetError on a missing, truncated, corrupt,
/// wrong-version or wrong-configuration file.
ClosureDetector LoadDatabase(const std::filesystem::path& file, const ClosureDetectorConfig& config);

}  // namespace revisit
