#include "io/newer_college.hpp"

#include <algorithm>

#include "core/error.hpp"
#include "io/stamped_layout.hpp"

namespace revisit {
namespace fs = std::filesystem;
namespace {

fs::path NewerCollegeScans(const fs::path& root) {
    for (const fs::path& candidate : {root / "raw_format" / "ouster_scan", root / "ouster_scan"}) {
        if (HasFileWithExtension(candidate, ".pcd")) return candidate;
    }
    return {};
}

/// "cloud_<sec>_<nsec>": the ROS header stamp of the scan, whole seconds and nanoseconds apart.
std::optional<std::uint64_t> CloudStem(const std::string& stem) {
    const std::string prefix = "cloud_";
    if (stem.compare(0, prefix.size(), prefix) != 0) return std::nullopt;
    const auto underscore = stem.find('_', prefix.size());
    if (underscore == std::string::npos) return std::nullopt;
    const auto sec = DigitStamp(stem.substr(prefix.size(), underscore - prefix.size()), 1000000000ull);
    const std::string nsec_text = stem.substr(underscore + 1);
    const auto nsec = nsec_text.size() <= 9 ? DigitStamp(nsec_text, 1) : std::nullopt;
    if (!sec || !nsec || *sec > UINT64_MAX - *nsec) return std::nullopt;
    return *sec + *nsec;
}

/// A scan PCD. Its Ouster `t` field counts nanoseconds since the sweep began (uint32); the PCD reader
/// takes time fields as seconds, so a span beyond a second (no sweep lasts that long) is nanoseconds.
CloudData LoadNewerCollegePcd(const fs::path& file) {
    CloudData cloud = LoadPcd(file);
    if (!cloud.point_times.empty() && *std::max_element(cloud.point_times.begin(), cloud.point_times.end()) > 1.0f) {
        for (float& t : cloud.point_times) t = static_cast<float>(t * 1e-9);
    }
    return cloud;
}

/// registered_poses.csv (2020) first, else the one gt-nc-*.csv or gt_state_*.csv (the maths sequences)
/// of the 2021 extension, in ground_truth/ or ROOT.
fs::path NewerCollegeReference(const fs::path& root) {
    if (fs::is_regular_file(root / "ground_truth" / "registered_poses.csv")) return root / "ground_truth" / "registered_poses.csv";
    std::vector<fs::path> found;
    for (const fs::path& folder : {root / "ground_truth", root}) {
        std::error_code ec;
        if (!fs::is_directory(folder, ec)) continue;
        for (const auto& entry : fs::directory_iterator(folder, ec)) {
            const std::string name = entry.path().filename().string();
            const bool ground_truth = name.rfind("gt-", 0) == 0 || name.rfind("gt_state_", 0) == 0;
            if (entry.is_regular_file() && ground_truth && entry.path().extension() == ".csv") found.push_back(entry.path());
        }
        if (!found.empty()) break;
    }
    if (found.size() > 1) {
        throw DatasetError(found[0].parent_path(), "several gt-*.csv / gt_state_*.csv ground truth files: give one with --gt");
    }
    return found.empty() ? fs::path() : found[0];
}

}  // namespace

bool IsNewerCollegeFolder(const fs::path& path) { return !NewerCollegeScans(path).empty(); }

std::unique_ptr<Reader> OpenNewerCollege(const fs::path& path, const ReaderOptions& options) {
    return OpenStampedLayout({"newer college", path,
                              ListStampedFiles(NewerCollegeScans(path), ".pcd", &CloudStem, "named cloud_<sec>_<nsec>.pcd by their stamp"),
                              &LoadNewerCollegePcd, "OUSTER", NewerCollegeReference(path), &ReadSecNsecPoses},
                             options);
}

}  // namespace revisit
