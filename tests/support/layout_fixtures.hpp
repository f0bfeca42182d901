#pragma once
/// The first scans of the shared KITTI sample laid out as the public datasets publish theirs.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "core/error.hpp"
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

/// The message of the DatasetError `action` throws, or "(no error)".
inline std::string DatasetErrorOf(const std::function<void()>& action) {
    try {
        action();
    } catch (const DatasetError& e) {
        return e.what();
    }
    return "(no error)";
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

/// [s] a point's time within its sweep, as the fixtures write it (0 .. 0.0999 s).
inline float PointTime(std::size_t p) { return static_cast<float>(p % 1000) * 1e-4f; }

constexpr std::uint64_t kNewerCollegeStart = 1583836591182590976ull;  ///< [ns] a Newer College 2020 clock
constexpr std::uint64_t kNcltStart = 1326030975726043ull;             ///< [us] an NCLT (2012-01-08) clock

inline std::string Stamp(std::uint64_t value) { return std::to_string(value); }

/// Newer College 2020: raw_format/ouster_scan/cloud_<sec>_<nsec>.pcd (binary PCD, x y z intensity t) and
/// ground_truth/registered_poses.csv (#sec,nsec,x,y,z,qx,qy,qz,qw) at twice the scan rate.
inline void MakeNewerCollege(const std::filesystem::path& root, const KittiSample& sample) {
    for (std::size_t i = 0; i < sample.scans.size(); ++i) {
        const std::uint64_t ns = kNewerCollegeStart + static_cast<std::uint64_t>(std::llround(sample.times[i] * 1e9));
        char name[64];
        std::snprintf(name, sizeof name, "cloud_%llu_%09llu.pcd", static_cast<unsigned long long>(ns / 1000000000ull),
                      static_cast<unsigned long long>(ns % 1000000000ull));
        const Scan& scan = sample.scans[i];
        std::string pcd = "# .PCD v0.7\nVERSION 0.7\nFIELDS x y z intensity t\nSIZE 4 4 4 4 4\nTYPE F F F F U\nCOUNT 1 1 1 1 1\nWIDTH " +
                          std::to_string(scan.points.size()) + "\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS " +
                          std::to_string(scan.points.size()) + "\nDATA binary\n";
        for (std::size_t p = 0; p < scan.points.size(); ++p) {
            for (int c = 0; c < 3; ++c) AppendRaw(pcd, scan.points[p][c]);
            AppendRaw(pcd, scan.intensities[p]);
            AppendRaw(pcd, static_cast<std::uint32_t>(std::lround(PointTime(p) * 1e9)));  // Ouster t [ns]
        }
        WriteBytes(root / "raw_format" / "ouster_scan" / name, pcd);
    }
    std::filesystem::create_directories(root / "ground_truth");
    std::ofstream csv(root / "ground_truth" / "registered_poses.csv");
    csv << "#sec,nsec,x,y,z,qx,qy,qz,qw\n";
    for (const auto& [t, T] : TwiceRatePoses(sample)) {
        const std::uint64_t ns = kNewerCollegeStart + static_cast<std::uint64_t>(std::llround(t * 1e9));
        const Eigen::Quaterniond q(T.linear());
        char line[256];
        std::snprintf(line, sizeof line, "%llu, %llu, %.9f, %.9f, %.9f, %.12f, %.12f, %.12f, %.12f\n",
                      static_cast<unsigned long long>(ns / 1000000000ull), static_cast<unsigned long long>(ns % 1000000000ull),
                      T.translation().x(), T.translation().y(), T.translation().z(), q.x(), q.y(), q.z(), q.w());
        csv << line;
    }
}

/// NCLT's frames have z down: the same 180-degree turn about x as the reader's, written out.
inline Eigen::Isometry3d Flip(const Eigen::Isometry3d& T) {
    Eigen::Isometry3d F = Eigen::Isometry3d::Identity();
    F.linear() = Eigen::Vector3d(1, -1, -1).asDiagonal();
    return F * T * F;
}

inline std::uint16_t NcltCount(float metres) { return static_cast<std::uint16_t>(std::lround((metres + 100.0) / 0.005)); }

/// NCLT: SESSION/velodyne_sync/<us>.bin (uint16 x, y, z scaled, uint8 intensity, uint8 laser) in the
/// z-down frame, and ground_truth/groundtruth_SESSION.csv (utime, x, y, z, roll, pitch, yaw) at twice
/// the scan rate, led by a row of NaN as the published files are.
inline void MakeNclt(const std::filesystem::path& root, const KittiSample& sample) {
    const std::filesystem::path session = root / "2012-01-08";
    for (std::size_t i = 0; i < sample.scans.size(); ++i) {
        std::string bin;
        const Scan& scan = sample.scans[i];
        for (std::size_t p = 0; p < scan.points.size(); ++p) {
            const Eigen::Vector3f& q = scan.points[p];
            AppendRaw(bin, NcltCount(q.x()));
            AppendRaw(bin, NcltCount(-q.y()));
            AppendRaw(bin, NcltCount(-q.z()));
            AppendRaw(bin, static_cast<std::uint8_t>(std::lround(scan.intensities[p] * 255.f)));
            AppendRaw(bin, static_cast<std::uint8_t>(p % 32));
        }
        const std::uint64_t us = kNcltStart + static_cast<std::uint64_t>(std::llround(sample.times[i] * 1e6));
        WriteBytes(session / "velodyne_sync" / (Stamp(us) + ".bin"), bin);
    }
    std::filesystem::create_directories(root / "ground_truth");
    std::ofstream csv(root / "ground_truth" / "groundtruth_2012-01-08.csv");
    csv << Stamp(kNcltStart - 50000) << ",nan,nan,nan,nan,nan,nan\n";
    for (const auto& [t, T_up] : TwiceRatePoses(sample)) {
        const Eigen::Isometry3d T = Flip(T_up);
        const Eigen::Vector3d ypr = T.linear().eulerAngles(2, 1, 0);  // R = Rz(yaw) Ry(pitch) Rx(roll)
        char line[256];
        std::snprintf(line, sizeof line, "%llu,%.9f,%.9f,%.9f,%.12f,%.12f,%.12f\n",
                      static_cast<unsigned long long>(kNcltStart + std::llround(t * 1e6)), T.translation().x(),
                      T.translation().y(), T.translation().z(), ypr[2], ypr[1], ypr[0]);
        csv << line;
    }
}

/// The published Aeva files gained an intensity field after this stamp: the fixture's clock starts
/// 0.25 s before it, so its first three scans have the older 25-byte layout and the rest 29 bytes.
constexpr std::uint64_t kAevaIntensitySince = 1691936557946849179ull;
constexpr std::uint64_t kHeLiPRStart = kAevaIntensitySince - 250000000ull;  ///< [ns]

inline std::uint64_t HeLiPRStamp(double t) { return kHeLiPRStart + static_cast<std::uint64_t>(std::llround(t * 1e9)); }

/// One scan in a sensor's published record layout (float32 x, y, z first in all of them).
inline std::string EncodeHeLiPR(const std::string& sensor, const Scan& scan, bool aeva_intensity) {
    std::string bin;
    for (std::size_t p = 0; p < scan.points.size(); ++p) {
        for (int c = 0; c < 3; ++c) AppendRaw(bin, scan.points[p][c]);
        const float intensity = scan.intensities[p];
        const auto ns = static_cast<std::uint32_t>(std::lround(PointTime(p) * 1e9));
        if (sensor == "Ouster") {
            AppendRaw(bin, intensity);
            AppendRaw(bin, ns);
            for (std::uint16_t v : {std::uint16_t(7), std::uint16_t(p % 128), std::uint16_t(300)}) AppendRaw(bin, v);
        } else if (sensor == "Velodyne") {
            AppendRaw(bin, intensity);
            AppendRaw(bin, static_cast<std::uint16_t>(p % 16));
            AppendRaw(bin, PointTime(p));
        } else if (sensor == "Avia") {
            AppendRaw(bin, static_cast<std::uint8_t>(std::lround(intensity * 255.f)));
            AppendRaw(bin, std::uint8_t(0));
            AppendRaw(bin, static_cast<std::uint8_t>(p % 6));
            AppendRaw(bin, ns);
        } else {  // Aeva: reflectivity, velocity, time_offset_ns, line_index [, intensity]
            AppendRaw(bin, aeva_intensity ? 0.5f : intensity);
            AppendRaw(bin, -1.25f);
            AppendRaw(bin, static_cast<std::int32_t>(ns));
            AppendRaw(bin, static_cast<std::uint8_t>(p % 64));
            if (aeva_intensity) AppendRaw(bin, intensity);
        }
    }
    return bin;
}

/// HeLiPR: LiDAR/<sensor>/<ns>.bin for the four sensors and LiDAR_GT/<sensor>_gt.txt (ns x y z qx qy qz
/// qw, space-separated) at twice the scan rate in UTM-like coordinates.
inline void MakeHeLiPR(const std::filesystem::path& root, const KittiSample& sample) {
    for (const std::string sensor : {"Ouster", "Velodyne", "Avia", "Aeva"}) {
        for (std::size_t i = 0; i < sample.scans.size(); ++i) {
            const std::uint64_t stamp = HeLiPRStamp(sample.times[i]);
            WriteBytes(root / "LiDAR" / sensor / (std::to_string(stamp) + ".bin"),
                             EncodeHeLiPR(sensor, sample.scans[i], stamp > kAevaIntensitySince));
        }
        std::filesystem::create_directories(root / "LiDAR_GT");
        std::ofstream gt(root / "LiDAR_GT" / (sensor + "_gt.txt"));
        for (const auto& [t, T] : TwiceRatePoses(sample)) {
            const Eigen::Quaterniond q(T.linear());
            char line[256];
            std::snprintf(line, sizeof line, "%llu %.9f %.9f %.9f %.12f %.12f %.12f %.12f\n",
                          static_cast<unsigned long long>(HeLiPRStamp(t)), T.translation().x() + 325000.0,
                          T.translation().y() + 4150000.0, T.translation().z() + 30.0, q.x(), q.y(), q.z(), q.w());
            gt << line;
        }
    }
}

}  // namespace revisit::test
