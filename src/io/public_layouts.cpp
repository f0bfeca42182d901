#include "io/public_layouts.hpp"

#include "core/error.hpp"
#include "io/stamped_layout.hpp"

namespace revisit {
namespace fs = std::filesystem;
namespace {

fs::path MulRanScans(const fs::path& root) {
    for (const fs::path& candidate : {root / "sensor_data" / "Ouster", root / "Ouster"}) {
        if (fs::is_directory(candidate)) return candidate;
    }
    return {};
}

/// ns stamp, then 12 numbers (3x4 row-major), comma-separated; UTM positions moved to the first pose.
Trajectory ReadMulRanPoses(const fs::path& file) {
    PoseTable table;
    table.lines = {13, "MulRan pose (a time stamp [ns] and 12 numbers: 3x4 pose)", true};
    table.move_to_first_position = true;
    table.to_pose = [&file](const std::vector<double>& v, std::size_t line) {
        Eigen::Matrix3d R;
        R << v[1], v[2], v[3], v[5], v[6], v[7], v[9], v[10], v[11];
        return std::make_pair(v[0] * 1e-9, CleanPose(R, Eigen::Vector3d(v[4], v[8], v[12]), file, line));
    };
    return ReadPoseTable(file, table);
}

}  // namespace

bool IsMulRanFolder(const fs::path& path) {
    return fs::is_regular_file(path / "global_pose.csv") && !MulRanScans(path).empty();
}

std::unique_ptr<Reader> OpenMulRan(const fs::path& path, const ReaderOptions& options) {
    return OpenStampedLayout({"mulran", path,
                              ListStampedFiles(MulRanScans(path), ".bin", &NanosecondStem, kNanosecondNames),
                              &LoadKittiBin, "OUSTER", path / "global_pose.csv", &ReadMulRanPoses},
                             options);
}

}  // namespace revisit
