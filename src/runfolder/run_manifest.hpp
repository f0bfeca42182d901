#pragma once
/// A run folder describes itself: run.json's `files` table lists every result file the chain wrote
/// with its size and CRC-32, and every reader of the folder (report, eval, inspect, merge, --against)
/// checks it before trusting a file. A file cut, edited or swapped after the run is a named error,
/// never read as the run's result.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "runfolder/run_folder.hpp"

namespace revisit {

struct ManifestEntry {
    std::string name;        ///< relative to the run folder, '/' separated ("maps/map_0000.bin")
    std::uintmax_t size = 0; ///< [bytes]
    std::uint32_t crc32 = 0; ///< zlib's CRC-32 of the whole file
};

/// Size and CRC-32 of `file`; throws DatasetError naming it when it cannot be read.
ManifestEntry DescribeFile(const std::filesystem::path& file, const std::string& name);

/// The entries of the chain's result files present in `run` (poses, CSV and JSON tables, closure
/// details, the database, the global map, config.yaml, run_options.json and maps/), sorted by name.
/// run.json itself and the evaluation's files (metrics.json, pr_curve_*.csv: `revisit eval` rewrites them) are not listed.
std::vector<ManifestEntry> ListRunFiles(const RunFolder& run);

/// The `files` table of run.json: {"name": {"size": N, "crc32": "8 hex digits"}, ...}.
nlohmann::json ManifestJson(const std::vector<ManifestEntry>& entries);

/// Checks every file of run.json's `files` table (`info`): present, of the listed size and CRC-32.
/// Throws DatasetError naming the file and what differs. A run without the table (written by an
/// earlier version) is not checked.
void CheckRunManifest(const RunFolder& run, const nlohmann::json& info);

}  // namespace revisit
