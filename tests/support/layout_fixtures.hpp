#pragma once
/// The first scans of the shared KITTI sample, for tests that lay them out as a public dataset does.
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

#include "core/pose_interpolation.hpp"
#include "io/trajectory_io.hpp"
#include "read_all.hpp"
#include "test_data.hpp"

namespace revisit::test {

struct KittiSample {
    std::vector<double> times;  ///< [s] from 0
    Poses poses;                ///< the LiDAR's, one per scan
    std::vector<Scan> scans;
};

/// The first `n` scans of ../shared/data/kitti00_first16 (REVISIT_REQUIRE_DATA it first).
inline KittiSample LoadKittiSample(std::size_t n) {
    const auto kitti = SharedData("kitti00_first16");
    KittiSample sample;
    auto scans = ReadAllScans(kitti);
    scans.resize(n);
    for (auto& scan : scans) {
        sample.times.push_back(scan.timestamp);
        sample.poses.push_back(*scan.T_world_sensor);
    }
    sample.scans = std::move(scans);
    return sample;
}

/// Reference poses at twice the scan rate: each scan's, and the midpoint to the next one, from scan
/// `first` on (earlier scans have none).
inline std::vector<std::pair<double, Eigen::Isometry3d>> TwiceRatePoses(const KittiSample& sample, std::size_t first = 0) {
    std::vector<std::pair<double, Eigen::Isometry3d>> poses;
    for (std::size_t i = first; i < sample.times.size(); ++i) {
        poses.emplace_back(sample.times[i], sample.poses[i]);
        if (i + 1 < sample.times.size()) {
            poses.emplace_back(0.5 * (sample.times[i] + sample.times[i + 1]), InterpolatePose(sample.poses[i], sample.poses[i + 1], 0.5));
        }
    }
    return poses;
}

/// `bytes` written to `file` as they are.
inline void WriteBytes(const std::filesystem::path& file, const std::string& bytes) {
    std::filesystem::create_directories(file.parent_path());
    std::ofstream(file, std::ios::binary) << bytes;
}

template <typename T>
void AppendRaw(std::string& bytes, T value) {
    bytes.append(reinterpret_cast<const char*>(&value), sizeof value);
}

}  // namespace revisit::test
