#include "io/reader.hpp"

#include <sstream>

#include "core/error.hpp"
#include "io/bag_source.hpp"
#include "io/carmen_reader.hpp"
#include "io/folder_reader.hpp"
#include "io/helipr.hpp"
#include "io/nclt.hpp"
#include "io/newer_college.hpp"
#include "io/public_layouts.hpp"
#include "io/rawlog_reader.hpp"
#include "io/writer.hpp"

namespace revisit {
namespace fs = std::filesystem;

namespace {

std::map<std::string, DatasetOpener>& Schemes() {
    static std::map<std::string, DatasetOpener> schemes;
    return schemes;
}

/// The scheme of "NAME:rest" when NAME is registered, else empty.
std::string SchemeOf(const std::string& spec) {
    const auto colon = spec.find(':');
    if (colon == std::string::npos || colon == 0) return {};
    const std::string scheme = spec.substr(0, colon);
    return Schemes().count(scheme) > 0 ? scheme : std::string();
}

}  // namespace

void RegisterDatasetScheme(const std::string& scheme, DatasetOpener opener) { Schemes()[scheme] = std::move(opener); }

bool IsSchemeDataset(const fs::path& path) { return !SchemeOf(path.string()).empty(); }

std::string DatasetName(const fs::path& path) {
    return IsSchemeDataset(path) ? path.string() : fs::absolute(path).string();
}

std::unique_ptr<Reader> OpenDataset(const fs::path& path, const ReaderOptions& options) {
    if (path.empty()) throw DatasetError(path, "no dataset path given");
    if (const std::string scheme = SchemeOf(path.string()); !scheme.empty()) return Schemes().at(scheme)(path.string(), options);
    std::error_code ec;
    const auto status = fs::status(path, ec);
    if (ec || !fs::exists(status)) throw DatasetError(path, "no such file or folder");
    if (fs::is_regular_file(status)) {
        if (HasCarmenExtension(path)) return OpenCarmenLog(path, options);
        if (HasRawlogExtension(path) || path.extension() == ".gz") {
            return OpenRawlog(path, options);
        }
        if (path.extension() == ".mcap") return OpenBag(OpenMcapSource(path, options), path, options);
        if (path.extension() == ".bag") return OpenBag(OpenRos1Source(path), path, options);
        if (path.extension() == ".db3" && IsRosbag2Folder(path.parent_path())) {
            return OpenBag(OpenDb3Source(path.parent_path()), path.parent_path(), options);
        }
        throw DatasetError(path, "unknown dataset format: expected a .rawlog, .mcap or .bag file, a CARMEN log (.log, .clf, also .gz / .bz2) or a folder (KITTI velodyne/, "
                                 ".pcd, .ply, rosbag2 metadata.yaml + .db3)");
    }
    if (!fs::is_directory(status)) throw DatasetError(path, "neither a file nor a folder");
    // The public layouts before KITTI: their folders are told apart by their own sub-folders.
    if (IsMulRanFolder(path)) return OpenMulRan(path, options);
    if (IsNewerCollegeFolder(path)) return OpenNewerCollege(path, options);
    if (IsNcltFolder(path)) return OpenNclt(path, options);
    if (IsHeLiPRFolder(path)) return OpenHeLiPR(path, options);
    if (IsKittiFolder(path)) return OpenKittiFolder(path, options);
    if (IsRosbag2Folder(path)) return OpenBag(OpenDb3Source(path), path, options);
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
