#pragma once
/// Single-scan point cloud files: KITTI .bin, PCD (ascii/binary) and PLY (ascii/binary little-endian).
#include <filesystem>
#include <string>
#include <vector>

#include "core/scan.hpp"

namespace revisit {

/// Points of one file; non-finite points are dropped and counted.
struct CloudData {
    std::vector<Eigen::Vector3f> points;
    std::vector<float> intensities;  ///< empty when the file has none
    std::vector<float> point_times;  ///< [s] relative, empty when the file has none
    std::size_t non_finite = 0;

    /// Appends one point (with the optional fields the cloud carries); drops it when not finite.
    void Add(float x, float y, float z, float intensity, float time);
    bool has_intensity = false;
    bool has_time = false;
};

/// A whole file of fixed-size point records of `record_size` bytes, after checking its size against
/// the records: a size that is not a whole number of records (a truncated or damaged file) is a
/// DatasetError naming the byte offset of the incomplete record and `layout` ("float32 x, y, z, ...").
std::string ReadPointRecords(const std::filesystem::path& file, std::size_t record_size, const std::string& layout);
/// float32 x, y, z, reflectance per point; throws DatasetError if the size is not a multiple of 16 bytes.
CloudData LoadKittiBin(const std::filesystem::path& file);
/// Fields x, y, z and optionally intensity and t/time/timestamp; DATA ascii or binary.
CloudData LoadPcd(const std::filesystem::path& file);
/// The vertex element's x, y, z and optionally intensity and t/time; ascii or binary_little_endian.
CloudData LoadPly(const std::filesystem::path& file);

/// Writes float32 x, y, z, intensity (0 when absent) per point.
void SaveKittiBin(const std::filesystem::path& file, const Scan& scan);
/// Binary little-endian PLY with x, y, z (float) and, if given, intensity.
void SavePly(const std::filesystem::path& file, const std::vector<Eigen::Vector3f>& points,
             const std::vector<float>& intensities = {});

/// KITTI's HDL-64E intrinsic error: rotate each point by 0.205 degrees about the horizontal axis
/// perpendicular to its azimuth (METHOD.md section 1).
void ApplyKittiVerticalCorrection(std::vector<Eigen::Vector3f>& points);

}  // namespace revisit
