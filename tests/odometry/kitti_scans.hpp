#pragma once
/// Test helper: the 16 real KITTI scans of ../shared/data/kitti00_first16, read directly
/// (float32 x, y, z, reflectance) so the odometry tests do not depend on the io module.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "core/scan.hpp"

namespace revisit::test {

inline std::filesystem::path KittiDir() {
    return std::filesystem::path(REVISIT_SHARED_DIR) / "data" / "kitti00_first16";
}

inline bool HaveKitti() { return std::filesystem::exists(KittiDir() / "velodyne" / "000015.bin"); }

/// Scan `index` with the 0.205 degree vertical-angle correction (METHOD.md section 1) when asked.
inline Scan LoadKittiScan(int index, bool vertical_correction = true) {
    char name[32];
    std::snprintf(name, sizeof(name), "%06d.bin", index);
    const auto file = KittiDir() / "velodyne" / name;
    std::vector<float> raw(std::filesystem::file_size(file) / sizeof(float));
    std::FILE* f = std::fopen(file.c_str(), "rb");
    const std::size_t read = f ? std::fread(raw.data(), sizeof(float), raw.size(), f) : 0;
    if (f) std::fclose(f);
    Scan scan;
    scan.index = static_cast<std::size_t>(index);
    scan.timestamp = 0.1 * index;
    scan.sensor_label = "VELODYNE";
    const double angle = 0.205 * M_PI / 180.0;
    for (std::size_t i = 0; i + 3 < read; i += 4) {
        Eigen::Vector3d p(raw[i], raw[i + 1], raw[i + 2]);
        const Eigen::Vector3d axis = p.cross(Eigen::Vector3d::UnitZ());
        if (vertical_correction && axis.norm() > 1e-9) p = Eigen::AngleAxisd(angle, axis.normalized()) * p;
        scan.points.push_back(p.cast<float>());
        scan.intensities.push_back(raw[i + 3]);
    }
    return scan;
}

}  // namespace revisit::test
