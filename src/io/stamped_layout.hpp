#pragma once
/// What the public dataset layouts share (MulRan, Newer College, NCLT, HeLiPR): one scan per file
/// named by its time stamp, a reference trajectory in the dataset's own text format paired with the
/// scans by time (io/timed_poses.hpp), and fixed-size binary point records.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/trajectory.hpp"
#include "io/folder_reader.hpp"
#include "io/reader.hpp"
#include "io/trajectory_io.hpp"

namespace revisit {

struct StampedFile {
    std::uint64_t stamp_ns = 0;  ///< [ns] from the file's name
    std::filesystem::path file;
};

/// The stamp [ns] a file stem names, or nothing when the stem is not of the layout's form.
using StampOfStem = std::optional<std::uint64_t> (*)(const std::string& stem);
/// A stem of digits only, read as a count of `ns_per_unit` nanoseconds (1: ns, 1000: us); nothing
/// for anything else or a value past 2^64 ns.
std::optional<std::uint64_t> DigitStamp(const std::string& stem, std::uint64_t ns_per_unit);

/// Stems of digits: nanoseconds (MulRan, HeLiPR) or microseconds (NCLT).
std::optional<std::uint64_t> NanosecondStem(const std::string& stem);
std::optional<std::uint64_t> MicrosecondStem(const std::string& stem);
inline const char* const kNanosecondNames = "named by their nanosecond time stamp (digits only)";
inline const char* const kMicrosecondNames = "named by their microsecond time stamp (digits only)";

/// True when `folder` holds at least one file ending in `extension` (".bin").
bool HasFileWithExtension(const std::filesystem::path& folder, const std::string& extension);
/// The files of `folder` ending in `extension`, sorted by stamp; a file whose name is not a stamp is
/// a DatasetError saying `naming` ("named by their nanosecond time stamp"), no file at all too.
std::vector<StampedFile> ListStampedFiles(const std::filesystem::path& folder, const std::string& extension,
                                          StampOfStem stamp_of, const std::string& naming);

/// A reference table: `lines` numbers per data line, each turned into (time [s], pose) by `to_pose`.
struct PoseTable {
    NumberLines lines;
    /// Shifts every position by the first one: UTM or similar coordinates (10^5..10^6 m) would lose
    /// centimetres in the float maps.
    bool move_to_first_position = false;
    std::function<std::pair<double, Eigen::Isometry3d>(const std::vector<double>&, std::size_t line)> to_pose;
};
/// Reads `file` as `table`; times must not decrease; no pose at all is a DatasetError.
Trajectory ReadPoseTable(const std::filesystem::path& file, const PoseTable& table);

/// A stamped scan layout ready to open.
struct StampedLayout {
    std::string format;                                ///< DatasetInfo::format
    std::filesystem::path path;                        ///< what the user gave
    std::vector<StampedFile> scans;
    CloudLoader loader = nullptr;
    std::string label;                                 ///< Scan::sensor_label
    std::filesystem::path reference_file;              ///< the dataset's own reference; empty: it has none
    std::function<Trajectory(const std::filesystem::path&)> read_reference;
    std::vector<TopicSummary> streams = {};            ///< for `revisit info`: the layout's other sensors, if any
};
/// The reader: `options.poses_file` (TUM or sec,nsec CSV: it must have times) replaces the dataset's
/// reference; either pairs with the scans by time stamp.
std::unique_ptr<Reader> OpenStampedLayout(StampedLayout layout, const ReaderOptions& options);

}  // namespace revisit
