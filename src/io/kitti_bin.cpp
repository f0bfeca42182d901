#include <cmath>
#include <cstdio>
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

namespace {
struct FileCloser {
    void operator()(std::FILE* f) const { std::fclose(f); }
};
using FilePtr = std::unique_ptr<std::FILE, FileCloser>;
}  // namespace

CloudData LoadKittiBin(const std::filesystem::path& file) {
    std::error_code ec;
    const auto bytes = std::filesystem::file_size(file, ec);
    if (ec) throw DatasetError(file, "cannot read: " + ec.message());
    if (bytes % (4 * sizeof(float)) != 0) {
        throw DatasetError(file, "size " + std::to_string(bytes) +
                                     " bytes is not a multiple of 16 (float32 x, y, z, intensity per point)");
    }
    const FilePtr f(std::fopen(file.c_str(), "rb"));
    if (!f) throw DatasetError(file, "cannot open for reading");
    std::vector<float> raw(bytes / sizeof(float));
    if (std::fread(raw.data(), sizeof(float), raw.size(), f.get()) != raw.size()) {
        throw DatasetError(file, "short read");
    }
    CloudData cloud;
    cloud.has_intensity = true;
    const std::size_t n = raw.size() / 4;
    cloud.points.reserve(n);
    cloud.intensities.reserve(n);
    for (std::size_t i = 0; i < n; ++i) cloud.Add(raw[4 * i], raw[4 * i + 1], raw[4 * i + 2], raw[4 * i + 3], 0.f);
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
