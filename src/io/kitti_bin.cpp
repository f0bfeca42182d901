#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "io/cloud_files.hpp"

namespace revisit {

void CloudData::Add(float x, float y, float z, float intensity, float time) {
    if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z)) {
        ++non_finite;
        return;
    }
    points.emplace_back(x, y, z);
    if (has_intensity) intensities.push_back(intensity);
    if (has_time) point_times.push_back(time);
}

std::string ReadPointRecords(const std::filesystem::path& file, std::size_t record_size, const std::string& layout) {
    std::error_code ec;
    const auto bytes = std::filesystem::file_size(file, ec);
    if (ec) throw DatasetError(file, "cannot read: " + ec.message());
    if (bytes % record_size != 0) {
        const auto complete = bytes - bytes % record_size;
        throw DatasetError(file, "size " + std::to_string(bytes) + " bytes is not a multiple of " + std::to_string(record_size) +
                                     " (one point: " + layout + "): the point at byte offset " +
                                     std::to_string(complete) + " has only " + std::to_string(bytes - complete) +
                                     " bytes (truncated or damaged file)");
    }
    const std::unique_ptr<std::FILE, int (*)(std::FILE*)> f(std::fopen(file.c_str(), "rb"), &std::fclose);
    if (!f) throw DatasetError(file, "cannot open for reading");
    std::string data(static_cast<std::size_t>(bytes), '\0');
    const std::size_t got = data.empty() ? 0 : std::fread(data.data(), 1, data.size(), f.get());
    if (got != data.size()) throw DatasetError(file, "short read at byte offset " + std::to_string(got));
    return data;
}

CloudData LoadKittiBin(const std::filesystem::path& file) {
    const std::string data = ReadPointRecords(file, 4 * sizeof(float), "float32 x, y, z, intensity");
    const std::size_t n = data.size() / (4 * sizeof(float));
    CloudData cloud;
    cloud.has_intensity = true;
    // CloudData::Add's rule written into sized arrays: a 64-beam scan has ~120,000 points, and a
    // push_back per field per point was a sixth of a pass over such scans.
    cloud.points.resize(n);
    cloud.intensities.resize(n);
    std::size_t kept = 0;
    float v[4];
    for (std::size_t i = 0; i < n; ++i) {
        std::memcpy(v, data.data() + i * sizeof v, sizeof v);
        const bool finite = std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]);
        cloud.points[kept] = Eigen::Vector3f(v[0], v[1], v[2]);
        cloud.intensities[kept] = v[3];
        kept += finite;
    }
    cloud.non_finite = n - kept;
    cloud.points.resize(kept);
    cloud.intensities.resize(kept);
    return cloud;
}

void SaveKittiBin(const std::filesystem::path& file, const Scan& scan) {
    std::vector<float> raw(4 * scan.points.size());
    for (std::size_t i = 0; i < scan.points.size(); ++i) {
        raw[4 * i] = scan.points[i].x();
        raw[4 * i + 1] = scan.points[i].y();
        raw[4 * i + 2] = scan.points[i].z();
        raw[4 * i + 3] = scan.has_intensities() ? scan.intensities[i] : 0.f;
    }
    WriteFileAtomically(file, std::string_view(reinterpret_cast<const char*>(raw.data()), raw.size() * sizeof(float)));
}

void ApplyKittiVerticalCorrection(std::vector<Eigen::Vector3f>& points) {
    const double angle = 0.205 * M_PI / 180.0;
    for (auto& p : points) {
        const Eigen::Vector3d point = p.cast<double>();
        const Eigen::Vector3d axis = point.cross(Eigen::Vector3d::UnitZ());
        if (axis.norm() < 1e-9) continue;  // on the vertical axis: no azimuth, nothing to correct
        p = (Eigen::AngleAxisd(angle, axis.normalized()) * point).cast<float>();
    }
}

}  // namespace revisit
