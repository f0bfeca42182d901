#pragma once
/// A plain point-to-point ICP for tests: the "fine 3D registration" used as truth for real map pairs.
#include <Eigen/Geometry>
#include <Eigen/SVD>
#include <cmath>
#include <unordered_map>
#include <vector>

namespace revisit::test {

struct GridIndex {
    double cell;
    std::unordered_map<long long, std::vector<Eigen::Vector3d>> cells;
    static long long Key(int x, int y, int z) {
        return ((long long)(x & 0x1fffff) << 42) | ((long long)(y & 0x1fffff) << 21) | (long long)(z & 0x1fffff);
    }
    GridIndex(const std::vector<Eigen::Vector3f>& points, double cell_size) : cell(cell_size) {
        for (const auto& p : points) {
            const Eigen::Vector3i k = (p.cast<double>() / cell).array().floor().cast<int>();
            cells[Key(k.x(), k.y(), k.z())].push_back(p.cast<double>());
        }
    }
    bool Nearest(const Eigen::Vector3d& q, double max_distance, Eigen::Vector3d* out) const {
        const Eigen::Vector3i k = (q / cell).array().floor().cast<int>();
        double best = max_distance * max_distance;
        bool found = false;
        for (int dx = -1; dx <= 1; ++dx)
            for (int dy = -1; dy <= 1; ++dy)
                for (int dz = -1; dz <= 1; ++dz) {
                    const auto it = cells.find(Key(k.x() + dx, k.y() + dy, k.z() + dz));
                    if (it == cells.end()) continue;
                    for (const auto& p : it->second) {
                        const double d = (p - q).squaredNorm();
                        if (d < best) best = d, *out = p, found = true;
                    }
                }
        return found;
    }
};

/// Refines T_target_source so that source points land on target points; coarse-to-fine gates.
inline Eigen::Isometry3d IcpPointToPoint(const std::vector<Eigen::Vector3f>& source,
                                         const std::vector<Eigen::Vector3f>& target, Eigen::Isometry3d T) {
    const GridIndex index(target, 1.5);
    for (double gate : {1.5, 1.0, 0.5, 0.3}) {
        for (int iteration = 0; iteration < 15; ++iteration) {
            Eigen::Vector3d ms = Eigen::Vector3d::Zero(), mt = Eigen::Vector3d::Zero();
            std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> pairs;
            for (std::size_t i = 0; i < source.size(); i += 2) {
                const Eigen::Vector3d s = T * source[i].cast<double>();
                Eigen::Vector3d t;
                if (index.Nearest(s, gate, &t)) pairs.push_back({s, t}), ms += s, mt += t;
            }
            if (pairs.size() < 10) return T;
            ms /= double(pairs.size());
            mt /= double(pairs.size());
            Eigen::Matrix3d H = Eigen::Matrix3d::Zero();
            for (const auto& [s, t] : pairs) H += (t - mt) * (s - ms).transpose();
            const Eigen::JacobiSVD<Eigen::Matrix3d> svd(H, Eigen::ComputeFullU | Eigen::ComputeFullV);
            Eigen::Matrix3d S = Eigen::Matrix3d::Identity();
            if ((svd.matrixU() * svd.matrixV().transpose()).determinant() < 0) S(2, 2) = -1;
            Eigen::Isometry3d delta = Eigen::Isometry3d::Identity();
            delta.linear() = svd.matrixU() * S * svd.matrixV().transpose();
            delta.translation() = mt - delta.linear() * ms;
            T = delta * T;
            if (delta.translation().norm() < 1e-5) break;
        }
    }
    return T;
}

}  // namespace revisit::test
