#include "io/reader.hpp"

#include <sstream>

#include "core/error.hpp"
#include "io/folder_reader.hpp"
#include "io/rawlog_reader.hpp"
#include "io/writer.hpp"

namespace revisit {
namespace fs = std::filesystem;

std::unique_ptr<Reader> OpenDataset(const fs::path& path, const ReaderOptions& options) {
    if (path.empty()) throw DatasetError(path, "no dataset path given");
    std::error_code ec;
    const auto status = fs::status(path, ec);
    if (ec || !fs::exists(status)) throw DatasetError(path, "no such file or folder");
    if (fs::is_regular_file(status)) {
        if (HasRawlogExtension(path) || path.extension() == ".gz") {
            return OpenRawlog(path, options);
        }
        throw DatasetError(path, "unknown dataset format: expected a .rawlog file or a folder (KITTI velodyne/, .pcd, .ply)");
    }
    if (!fs::is_directory(status)) throw DatasetError(path, "neither a file nor a folder");
    if (IsKittiFolder(path)) return OpenKittiFolder(path, options);
    if (fs::is_directory(path / "sequences")) {
        throw DatasetError(path, "this is a KITTI dataset root: give one sequence, e.g. " + (path / "sequences" / "00").string());
    }
    return OpenCloudFolder(path, options);
}

std::string DescribeDrops(const ReadStats& stats) {
    std::ostringstream out;
    const char* separator = "";
    if (stats.non_finite_points > 0) {
        out << "dropped " << stats.non_finite_points << " NaN/inf points";
        separator = "; ";
    }
    if (!stats.skipped_classes.empty()) {
        out << separator << "skipped objects without scans:";
        for (const auto& [name, count] : stats.skipped_classes) out << ' ' << name << " x" << count;
        separator = "; ";
    }
    if (!stats.skipped_sensors.empty()) {
        out << separator << "skipped other sensors:";
        for (const auto& [label, count] : stats.skipped_sensors) out << ' ' << (label.empty() ? "(no label)" : label) << " x" << count;
    }
    return out.str();
}

}  // namespace revisit
