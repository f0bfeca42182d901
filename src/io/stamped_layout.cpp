#include "io/stamped_layout.hpp"

#include <algorithm>
#include <limits>

#include "core/error.hpp"

namespace revisit {
namespace fs = std::filesystem;

std::optional<std::uint64_t> DigitStamp(const std::string& stem, std::uint64_t ns_per_unit) {
    if (stem.empty() || stem.size() > 20 || !std::all_of(stem.begin(), stem.end(), [](char c) { return c >= '0' && c <= '9'; })) {
        return std::nullopt;
    }
    std::uint64_t value = 0;
    for (const char c : stem) {
        const auto digit = static_cast<std::uint64_t>(c - '0');
        if (value > (std::numeric_limits<std::uint64_t>::max() - digit) / 10) return std::nullopt;
        value = value * 10 + digit;
    }
    if (value > std::numeric_limits<std::uint64_t>::max() / ns_per_unit) return std::nullopt;
    return value * ns_per_unit;
}

std::optional<std::uint64_t> NanosecondStem(const std::string& stem) { return DigitStamp(stem, 1); }
std::optional<std::uint64_t> MicrosecondStem(const std::string& stem) { return DigitStamp(stem, 1000); }

bool HasFileWithExtension(const fs::path& folder, const std::string& extension) {
    std::error_code ec;
    if (!fs::is_directory(folder, ec)) return false;
    for (const auto& entry : fs::directory_iterator(folder, ec)) {
        if (entry.is_regular_file() && entry.path().extension() == extension) return true;
    }
    return false;
}

std::vector<StampedFile> ListStampedFiles(const fs::path& folder, const std::string& extension, StampOfStem stamp_of,
                                          const std::string& naming) {
    std::vector<StampedFile> stamped;
    for (const auto& entry : fs::directory_iterator(folder)) {
        if (!entry.is_regular_file() || entry.path().extension() != extension) continue;
        const auto stamp = stamp_of(entry.path().stem().string());
        if (!stamp) throw DatasetError(entry.path(), "the scans of this layout are " + naming);
        stamped.push_back({*stamp, entry.path()});
    }
    if (stamped.empty()) throw DatasetError(folder, "no " + extension + " scans");
    std::sort(stamped.begin(), stamped.end(), [](const StampedFile& a, const StampedFile& b) {
        return a.stamp_ns != b.stamp_ns ? a.stamp_ns < b.stamp_ns : a.file < b.file;
    });
    return stamped;
}

Trajectory ReadPoseTable(const fs::path& file, const PoseTable& table) {
    Trajectory trajectory;
    Eigen::Vector3d origin = Eigen::Vector3d::Zero();
    ForEachNumberLine(file, table.lines, [&](const std::vector<double>& values, std::size_t line) {
        auto [t, T] = table.to_pose(values, line);
        if (trajectory.empty() && table.move_to_first_position) origin = T.translation();
        T.translation() -= origin;
        AppendStampedPose(trajectory, t, T, file, line);
    });
    if (trajectory.empty()) throw DatasetError(file, "no poses");
    return trajectory;
}

std::unique_ptr<Reader> OpenStampedLayout(StampedLayout layout, const ReaderOptions& options) {
    DatasetInfo info;
    info.format = layout.format;
    info.path = layout.path;
    info.topics = std::move(layout.streams);
    Trajectory reference;
    if (!options.poses_file.empty()) {
        info.poses_file = options.poses_file;
        reference = ReadPoses(options.poses_file);
        if (!reference.has_timestamps()) {
            throw DatasetError(options.poses_file, info.format + " scans pair with reference poses by time stamp: give a TUM file");
        }
    } else if (!layout.reference_file.empty()) {
        info.poses_file = layout.reference_file;
        reference = layout.read_reference(layout.reference_file);
    }
    std::vector<fs::path> files;
    std::vector<double> times;
    files.reserve(layout.scans.size());
    times.reserve(layout.scans.size());
    for (auto& scan : layout.scans) {
        files.push_back(std::move(scan.file));
        // Whole seconds and the fraction apart: a double of 1.6e18 ns would round to 256 ns.
        times.push_back(static_cast<double>(scan.stamp_ns / 1000000000ull) + static_cast<double>(scan.stamp_ns % 1000000000ull) * 1e-9);
    }
    return OpenStampedScanFiles(std::move(info), std::move(files), layout.loader, std::move(layout.label), std::move(times),
                                std::move(reference), options);
}

}  // namespace revisit
