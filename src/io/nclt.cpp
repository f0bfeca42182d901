#include "io/nclt.hpp"

#include <cstring>

#include "core/error.hpp"
#include "io/stamped_layout.hpp"

namespace revisit {
namespace fs = std::filesystem;
namespace {

constexpr std::size_t kPointBytes = 8;   ///< uint16 x, y, z, uint8 intensity, uint8 laser id
constexpr double kScale = 0.005;         ///< [m] per count (NCLT's read_vel_sync.py)
constexpr double kOffset = -100.0;       ///< [m] at count 0

/// NCLT's body, Velodyne and world frames are x forward, y right, z down; revisit's are z up.
/// A 180-degree turn about x maps one to the other and is its own inverse.
const Eigen::Isometry3d& T_up_down() {
    static const Eigen::Isometry3d T = [] {
        Eigen::Isometry3d flip = Eigen::Isometry3d::Identity();
        flip.linear() = Eigen::Vector3d(1.0, -1.0, -1.0).asDiagonal();
        return flip;
    }();
    return T;
}

/// utime [us], x, y, z [m], roll, pitch, yaw [rad] (R = Rz(yaw) Ry(pitch) Rx(roll)), comma-separated.
Trajectory ReadNcltGroundTruth(const fs::path& file) {
    PoseTable table;
    table.lines = {7, "NCLT ground truth (utime, x, y, z, roll, pitch, yaw)", true, true};
    table.to_pose = [&file](const std::vector<double>& v, std::size_t line) {
        const Eigen::Matrix3d R = (Eigen::AngleAxisd(v[6], Eigen::Vector3d::UnitZ()) *
                                   Eigen::AngleAxisd(v[5], Eigen::Vector3d::UnitY()) *
                                   Eigen::AngleAxisd(v[4], Eigen::Vector3d::UnitX()))
                                      .toRotationMatrix();
        const Eigen::Isometry3d T_world_body = CleanPose(R, Eigen::Vector3d(v[1], v[2], v[3]), file, line);
        return std::make_pair(v[0] * 1e-6, Eigen::Isometry3d(T_up_down() * T_world_body * T_up_down()));
    };
    return ReadPoseTable(file, table);
}

fs::path NcltGroundTruth(const fs::path& root) {
    const fs::path absolute = fs::absolute(root).lexically_normal();
    const fs::path session = absolute.filename().empty() ? absolute.parent_path() : absolute;
    const std::string name = "groundtruth_" + session.filename().string() + ".csv";
    for (const fs::path& candidate : {session / name, session.parent_path() / name, session.parent_path() / "ground_truth" / name}) {
        if (fs::is_regular_file(candidate)) return candidate;
    }
    return {};
}

/// The session folder, also when the user names its velodyne_sync/ folder.
fs::path SessionOf(const fs::path& path) {
    const fs::path trimmed = path.filename().empty() ? path.parent_path() : path;
    return trimmed.filename() == "velodyne_sync" ? trimmed.parent_path() : path;
}

}  // namespace

bool IsNcltFolder(const fs::path& path) { return HasFileWithExtension(SessionOf(path) / "velodyne_sync", ".bin"); }

CloudData LoadNcltBin(const fs::path& file) {
    const std::string data = ReadPointRecords(file, kPointBytes, "uint16 x, y, z, uint8 intensity, uint8 laser id");
    const std::size_t n = data.size() / kPointBytes;
    CloudData cloud;
    cloud.has_intensity = true;
    cloud.points.reserve(n);
    cloud.intensities.reserve(n);
    for (std::size_t i = 0; i < n; ++i) {
        const char* record = data.data() + i * kPointBytes;
        std::uint16_t xyz[3];
        std::memcpy(xyz, record, sizeof xyz);  // little-endian, as the host
        const auto metres = [](std::uint16_t count) { return static_cast<float>(count * kScale + kOffset); };
        cloud.Add(metres(xyz[0]), -metres(xyz[1]), -metres(xyz[2]), static_cast<float>(static_cast<unsigned char>(record[6])), 0.f);
    }
    return cloud;
}

std::unique_ptr<Reader> OpenNclt(const fs::path& given, const ReaderOptions& options) {
    const fs::path path = SessionOf(given);
    return OpenStampedLayout({"nclt", given,
                              ListStampedFiles(path / "velodyne_sync", ".bin", &MicrosecondStem, kMicrosecondNames),
                              &LoadNcltBin, "VELODYNE", NcltGroundTruth(path), &ReadNcltGroundTruth},
                             options);
}

}  // namespace revisit
