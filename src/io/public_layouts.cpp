#include "io/public_layouts.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>

#include "core/error.hpp"
#include "core/se3.hpp"
#include "io/folder_reader.hpp"
#include "io/trajectory_io.hpp"

namespace revisit {
namespace fs = std::filesystem;
namespace {

fs::path MulRanScans(const fs::path& root) {
    for (const fs::path& candidate : {root / "sensor_data" / "Ouster", root / "Ouster"}) {
        if (fs::is_directory(candidate)) return candidate;
    }
    return {};
}

/// The nanosecond stamp a file is named by; anything else in the name is an error.
std::uint64_t StampOfName(const fs::path& file) {
    const std::string stem = file.stem().string();
    if (stem.empty() || stem.size() > 19 || !std::all_of(stem.begin(), stem.end(), [](char c) { return c >= '0' && c <= '9'; })) {
        throw DatasetError(file, "MulRan scans are named by their nanosecond time stamp (digits only)");
    }
    return std::stoull(stem);
}

/// ns stamp, then 12 numbers (3x4 row-major), comma-separated; UTM positions moved to the first pose.
Trajectory ReadMulRanPoses(const fs::path& file) {
    std::ifstream in(file);
    if (!in) throw DatasetError(file, "cannot open");
    Trajectory trajectory;
    std::string line;
    Eigen::Vector3d origin = Eigen::Vector3d::Zero();
    for (std::size_t line_number = 1; std::getline(in, line); ++line_number) {
        if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
        std::replace(line.begin(), line.end(), ',', ' ');
        const char* cursor = line.c_str();
        double v[13];
        for (int i = 0; i < 13; ++i) {
            char* end = nullptr;
            v[i] = std::strtod(cursor, &end);
            if (end == cursor || !std::isfinite(v[i])) {
                throw DatasetError(file, "expected a time stamp [ns] and 12 numbers (3x4 pose), comma-separated", line_number);
            }
            cursor = end;
        }
        if (std::string(cursor).find_first_not_of(" \t\r") != std::string::npos) {
            throw DatasetError(file, "more than 13 values on the line", line_number);
        }
        const double t = v[0] * 1e-9;
        if (!trajectory.timestamps.empty() && t < trajectory.timestamps.back()) {
            throw DatasetError(file, "time stamps go backwards", line_number);
        }
        Eigen::Matrix3d R;
        R << v[1], v[2], v[3], v[5], v[6], v[7], v[9], v[10], v[11];
        const Eigen::Matrix3d R_clean = NearestRotation(R);
        if ((R_clean - R).norm() > 1e-2) throw DatasetError(file, "rotation part is not a rotation matrix", line_number);
        const Eigen::Vector3d p(v[4], v[8], v[12]);
        if (trajectory.empty()) origin = p;
        Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
        T.linear() = R_clean;
        T.translation() = p - origin;  // UTM metres (10^6) would lose centimetres in float maps
        trajectory.timestamps.push_back(t);
        trajectory.poses.push_back(T);
    }
    if (trajectory.empty()) throw DatasetError(file, "no poses");
    return trajectory;
}

}  // namespace

bool IsMulRanFolder(const fs::path& path) {
    return fs::is_regular_file(path / "global_pose.csv") && !MulRanScans(path).empty();
}

std::unique_ptr<Reader> OpenMulRan(const fs::path& path, const ReaderOptions& options) {
    const fs::path folder = MulRanScans(path);
    std::vector<std::pair<std::uint64_t, fs::path>> stamped;
    for (const auto& entry : fs::directory_iterator(folder)) {
        if (entry.is_regular_file() && entry.path().extension() == ".bin") stamped.emplace_back(StampOfName(entry.path()), entry.path());
    }
    if (stamped.empty()) throw DatasetError(folder, "no .bin scans");
    std::sort(stamped.begin(), stamped.end());
    std::vector<fs::path> files;
    std::vector<double> times;
    for (const auto& [stamp, file] : stamped) {
        files.push_back(file);
        times.push_back(static_cast<double>(stamp) * 1e-9);
    }
    DatasetInfo info;
    info.format = "mulran";
    info.path = path;
    info.poses_file = options.poses_file.empty() ? path / "global_pose.csv" : options.poses_file;
    Trajectory reference = options.poses_file.empty() ? ReadMulRanPoses(info.poses_file) : ReadPoses(options.poses_file);
    if (!reference.has_timestamps()) {
        throw DatasetError(info.poses_file, "MulRan scans pair with reference poses by time stamp: give a TUM file");
    }
    return OpenStampedScanFiles(std::move(info), std::move(files), &LoadKittiBin, "OUSTER", std::move(times), std::move(reference),
                                options);
}

}  // namespace revisit
