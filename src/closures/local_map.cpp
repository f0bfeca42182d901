#include "closures/local_map.hpp"

#include <cmath>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace revisit {

LocalMapper::LocalMapper(const LocalMapConfig& config) : config_(config) {}

Eigen::Vector3i LocalMapper::KeyOf(const Eigen::Vector3f& point_in_map) const {
    return FloorVoxel(Eigen::Vector3f(point_in_map / float(config_.voxel_size)));
}

void LocalMapper::Insert(const Eigen::Vector3f& point_in_map) {
    const Eigen::Vector3i key = KeyOf(point_in_map);
    auto& voxel = voxels_[key];
    if (int(voxel.size()) >= config_.max_points_per_voxel) return;
    voxel.push_back(point_in_map);
    if (int(voxel.size()) == config_.max_points_per_voxel) full_voxels_.insert(key);
}

void LocalMapper::StartMap(std::size_t scan_index, const Eigen::Isometry3d& T_world_sensor) {
    current_ = LocalMap{};
    current_.id = next_id_++;
    current_.first_scan = scan_index;
    current_.last_scan = scan_index;
    current_.T_world_map = T_world_sensor;
    current_.travel_start = travel_;
    has_current_ = true;
}

LocalMap LocalMapper::CloseCurrent() {
    LocalMap map = std::move(current_);
    std::size_t count = 0;
    for (const auto& [key, voxel] : voxels_) count += voxel.size();
    map.points.reserve(count);
    for (const auto& [key, voxel] : voxels_) map.points.insert(map.points.end(), voxel.begin(), voxel.end());
    has_current_ = false;
    return map;
}

std::optional<LocalMap> LocalMapper::AddScan(std::size_t scan_index, const Eigen::Vector3f* points_in_sensor,
                                             std::size_t count, const Eigen::Isometry3d& T_world_sensor) {
    const Eigen::Vector3d position = T_world_sensor.translation();
    if (last_position_) travel_ += (position - *last_position_).norm();
    last_position_ = position;

    std::optional<LocalMap> closed;
    if (has_current_) {
        // METHOD.md section 2: paper splits by travelled distance, later code by straight-line distance.
        const double distance = config_.straight_line_split
                                    ? (position - current_.T_world_map.translation()).norm()
                                    : travel_ - current_.travel_start;
        const bool too_wide = config_.max_extent > 0.0 &&
                              (position - current_.T_world_map.translation()).norm() > config_.max_extent;
        if (distance > config_.split_distance || too_wide) {
            const Eigen::Isometry3d T_world_old = current_.T_world_map;
            closed = CloseCurrent();
            voxels_.clear();
            full_voxels_.clear();
            StartMap(scan_index, T_world_sensor);
            if (config_.carry_over) {
                // Later code: points within max_range of the new origin overlap into the next map.
                const Eigen::Isometry3f T_new_old = (T_world_sensor.inverse() * T_world_old).cast<float>();
                const float radius2 = float(config_.carry_radius * config_.carry_radius);
                for (const auto& p : closed->points) {
                    const Eigen::Vector3f q = T_new_old * p;
                    if (q.squaredNorm() < radius2) Insert(q);
                }
            }
        }
    }
    if (!has_current_) StartMap(scan_index, T_world_sensor);

    const Eigen::Isometry3d T_map_scan = current_.T_world_map.inverse() * T_world_sensor;
    const Eigen::Isometry3f T_map_scan_f = T_map_scan.cast<float>();
    const std::size_t n = count;
    if (n < 16384) {  // small scans: the plain loop, no tasks
        for (std::size_t i = 0; i < n; ++i) Insert(T_map_scan_f * points_in_sensor[i]);
    } else {
        // In parallel (issue 19): the transform, and whether the point's voxel is already full. A full
        // voxel never changes again, so skipping its points is exact; the serial insertion, in input
        // order as before, only sees the points that can still enter the map. The index is only read.
        points_in_map_.resize(n);
        full_.resize(n);
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 8192), [&](const auto& range) {
            for (std::size_t i = range.begin(); i != range.end(); ++i) {
                points_in_map_[i] = T_map_scan_f * points_in_sensor[i];
                full_[i] = full_voxels_.count(KeyOf(points_in_map_[i])) != 0;
            }
        });
        for (std::size_t i = 0; i < n; ++i)
            if (!full_[i]) Insert(points_in_map_[i]);
    }
    current_.last_scan = scan_index;
    current_.travel_end = travel_;
    current_.T_map_scan.push_back(T_map_scan);
    return closed;
}

std::optional<LocalMap> LocalMapper::Finish() {
    if (!has_current_) return std::nullopt;
    LocalMap map = CloseCurrent();
    voxels_.clear();
    full_voxels_.clear();
    return map;
}

std::vector<LocalMap> BuildLocalMaps(const std::vector<std::vector<Eigen::Vector3f>>& scans_in_sensor,
                                     const std::vector<Eigen::Isometry3d>& T_world_sensor, const LocalMapConfig& config) {
    LocalMapper mapper(config);
    std::vector<LocalMap> maps;
    for (std::size_t i = 0; i < scans_in_sensor.size() && i < T_world_sensor.size(); ++i) {
        if (auto map = mapper.AddScan(i, scans_in_sensor[i], T_world_sensor[i])) maps.push_back(std::move(*map));
    }
    if (auto map = mapper.Finish()) maps.push_back(std::move(*map));
    return maps;
}

}  // namespace revisit
