#pragma once
/// Point clouds for the refinement tests: a real KITTI scan (when ../shared is present)
/// and a synthetic street scene that needs no data.
#include <Eigen/Core>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

namespace revisit::testing {

inline std::filesystem::path Kitti00First16() { return std::filesystem::path(REVISIT_SHARED_DIR) / "data/kitti00_first16"; }

/// KITTI velodyne .bin: float32 x, y, z, reflectance; points only. Empty if the file is missing.
inline std::vector<Eigen::Vector3d> ReadKittiBin(const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    std::vector<Eigen::Vector3d> points;
    float record[4];
    while (in.read(reinterpret_cast<char*>(record), sizeof(record))) points.emplace_back(record[0], record[1], record[2]);
    return points;
}

/// Every `stride`-th point starting at `offset`: two disjoint samplings of one cloud.
inline std::vector<Eigen::Vector3d> Subsample(const std::vector<Eigen::Vector3d>& points, std::size_t stride, std::size_t offset) {
    std::vector<Eigen::Vector3d> kept;
    for (std::size_t i = offset; i < points.size(); i += stride) kept.push_back(points[i]);
    return kept;
}

inline std::vector<Eigen::Vector3d> Transform(const Eigen::Isometry3d& T, const std::vector<Eigen::Vector3d>& points) {
    std::vector<Eigen::Vector3d> moved;
    moved.reserve(points.size());
    for (const auto& p : points) moved.push_back(T * p);
    return moved;
}

/// A street of `length` metres: ground, two facades with recesses, poles and parked boxes,
/// sampled uniformly at random (density ~ points per m^2) with 1 cm noise.
inline std::vector<Eigen::Vector3d> SyntheticStreet(double length, double density, std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::normal_distribution<double> noise(0.0, 0.01);
    std::vector<Eigen::Vector3d> points;
    auto sample_rectangle = [&](const Eigen::Vector3d& origin, const Eigen::Vector3d& u, const Eigen::Vector3d& v) {
        const int count = static_cast<int>(u.norm() * v.norm() * density);
        for (int i = 0; i < count; ++i) {
            const Eigen::Vector3d p = origin + unit(rng) * u + unit(rng) * v;
            points.emplace_back(p + Eigen::Vector3d(noise(rng), noise(rng), noise(rng)));
        }
    };
    const double half = length / 2.0;
    sample_rectangle({-half, -12.0, 0.0}, {length, 0, 0}, {0, 24.0, 0});  // ground
    for (double x = -half; x < half; x += 10.0) {
        // Facades alternate depth every 10 m so the street does not slide along itself.
        const double left = 8.0 + 1.5 * std::sin(x * 0.37);
        const double right = -8.0 - 1.5 * std::cos(x * 0.23);
        sample_rectangle({x, left, 0.0}, {10.0, 0, 0}, {0, 0, 6.0 + 2.0 * unit(rng)});
        sample_rectangle({x, right, 0.0}, {10.0, 0, 0}, {0, 0, 6.0 + 2.0 * unit(rng)});
        sample_rectangle({x, right, 0.0}, {0, right + 12.0, 0}, {0, 0, 5.0});  // recess side walls
        // A parked box and a pole per block.
        const double bx = x + 2.0 + 6.0 * unit(rng);
        const double by = (unit(rng) < 0.5 ? 1.0 : -1.0) * (4.0 + 2.0 * unit(rng));
        sample_rectangle({bx, by, 0.0}, {4.0, 0, 0}, {0, 0, 1.5});
        sample_rectangle({bx, by, 0.0}, {0, 1.8, 0}, {0, 0, 1.5});
        sample_rectangle({bx, by, 1.5}, {4.0, 0, 0}, {0, 1.8, 0});
        const double px = x + 10.0 * unit(rng);
        sample_rectangle({px, 6.0, 0.0}, {0.3, 0, 0}, {0, 0, 4.0});
        sample_rectangle({px, 6.0, 0.0}, {0, 0.3, 0}, {0, 0, 4.0});
    }
    return points;
}

}  // namespace revisit::testing
