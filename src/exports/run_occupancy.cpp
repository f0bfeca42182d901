#include "exports/run_occupancy.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <utility>

#include <tsl/robin_map.h>
#include <tsl/robin_set.h>

#include "closures/ground_alignment.hpp"
#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "core/mix_bits.hpp"
#include "core/quantile.hpp"
#include "runfolder/folder_map_store.hpp"
#include "runfolder/planar_scans.hpp"

namespace revisit {
namespace fs = std::filesystem;

namespace {

constexpr double kLaserResolution = 0.05;  ///< [m] what 2D laser maps are commonly served at

Eigen::Vector2d Xy(const Eigen::Vector3d& p) { return p.head<2>(); }

/// Counts the maps done for the caller's progress.
struct MapCounter {
    const OccupancyProgress& on_map;
    std::size_t total;
    std::size_t done = 0;
    void Next() {
        if (on_map) on_map(++done, total);
    }
};

const Eigen::Isometry3d& ScanPose(const RunFolder& run, const RunState& state, int map_id, const PlanarScan& scan) {
    if (scan.position >= state.corrected.size()) {
        throw DatasetError(PlanarScansFile(run, map_id), "scan position " + std::to_string(scan.position) + " is past the run's " +
                                                             std::to_string(state.corrected.size()) + " poses");
    }
    return state.corrected[scan.position];
}

/// Traces every stored beam twice over the maps: once for the extent, once into the grid.
OccupancyGrid PlanarOccupancy(const RunFolder& run, const RunState& state, const OccupancyConfig& config,
                             const OccupancyProgress& on_map) {
    MapCounter counted{on_map, 2 * state.maps.size()};
    Eigen::AlignedBox2d extent;
    for (const auto& map : state.maps) {
        for (const auto& scan : ReadPlanarScans(run, map.id)) {
            const Eigen::Isometry3d& T_world_sensor = ScanPose(run, state, map.id, scan);
            extent.extend(Xy(T_world_sensor.translation()));
            for (const auto& p : scan.points_in_sensor) extent.extend(Xy(T_world_sensor * Eigen::Vector3d(p.x(), p.y(), 0.0)));
        }
        counted.Next();
    }
    if (!state.maps.empty() && extent.isEmpty() && !fs::exists(PlanarScansFile(run, state.maps.front().id))) {
        throw DatasetError(run.maps_dir(), "holds no scans_NNNN.bin: this 2D run was made by a revisit that did not keep its "
                                           "scans for the occupancy grid; run it again");
    }
    const double wanted = config.resolution > 0.0 ? config.resolution : kLaserResolution;
    OccupancyGrid grid(extent, FittingResolution(extent, wanted, config.max_cells_per_side));
    for (const auto& map : state.maps) {
        for (const auto& scan : ReadPlanarScans(run, map.id)) {
            const Eigen::Isometry3d& T_world_sensor = ScanPose(run, state, map.id, scan);
            const Eigen::Vector2d from = Xy(T_world_sensor.translation());
            for (const auto& p : scan.points_in_sensor) grid.AddRay(from, Xy(T_world_sensor * Eigen::Vector3d(p.x(), p.y(), 0.0)));
        }
        counted.Next();
    }
    return grid;
}

/// A point's height above the ground beside it: the lowest point within one ground cell of its own, in
/// the map's levelled frame. One plane per map does not follow a campus's terraces and slopes (a
/// handheld walk's maps span metres of height); the lowest point nearby does, and a wall seen down to
/// the floor stands on it.
class LocalGround {
  public:
    using Cell = std::pair<long, long>;
    struct CellHash {
        std::size_t operator()(const Cell& k) const {
            return std::size_t(MixBits((std::uint64_t(k.first) << 32) ^ (std::uint64_t(k.second) & 0xffffffffu)));
        }
    };

    LocalGround(const std::vector<Eigen::Vector3d>& points_levelled, double cell) : cell_(cell) {
        tsl::robin_map<Cell, double, CellHash> lowest;
        for (const auto& q : points_levelled) {
            const auto [it, added] = lowest.try_emplace(Key(q), q.z());
            if (!added && q.z() < it->second) it.value() = q.z();
        }
        // Each occupied cell's ground, the lowest of the 3 x 3 cells around it, once per cell: a map's
        // points share few cells, and the heights are asked point by point (the same minimum).
        ground_.reserve(lowest.size());
        for (const auto& [key, own] : lowest) {
            double ground = own;
            for (long dx = -1; dx <= 1; ++dx) {
                for (long dy = -1; dy <= 1; ++dy) {
                    const auto it = lowest.find({key.first + dx, key.second + dy});
                    if (it != lowest.end()) ground = std::min(ground, it->second);
                }
            }
            ground_.emplace(key, ground);
        }
    }
    /// The cells within one cell of `cells` (the sensor's path), for Beside.
    static tsl::robin_set<Cell, CellHash> Around(const std::vector<Cell>& cells) {
        tsl::robin_set<Cell, CellHash> around;
        for (const auto& [x, y] : cells)
            for (long dx = -1; dx <= 1; ++dx)
                for (long dy = -1; dy <= 1; ++dy) around.insert({x + dx, y + dy});
        return around;
    }
    /// Whether `q` lies within one cell of the path whose cells Around gave.
    bool Beside(const Eigen::Vector3d& q, const tsl::robin_set<Cell, CellHash>& around_path) const {
        return around_path.count(Key(q)) != 0;
    }
    Cell Key(const Eigen::Vector3d& q) const {
        return {static_cast<long>(std::floor(q.x() / cell_)), static_cast<long>(std::floor(q.y() / cell_))};
    }
    /// `q` is one of the points the ground was made of (its cell is occupied).
    double HeightOf(const Eigen::Vector3d& q) const {
        const auto it = ground_.find(Key(q));
        return q.z() - (it == ground_.end() ? q.z() : std::min(q.z(), it->second));
    }

  private:
    double cell_;
    tsl::robin_map<Cell, double, CellHash> ground_;  ///< per occupied cell: the lowest point within one cell
};

/// One map's points: (x, y) in the first map's levelled frame and the height above the ground beside it,
/// with the thickness of the ground where the sensor went.
struct MapHeights {
    std::vector<std::pair<Eigen::Vector2d, double>> points;
    double ground_thickness = 0.0;  ///< [m]
};

/// A 3D run's grid: heights above the ground beside each point (LocalGround, in each map's levelled
/// frame), positions in the first map's levelled frame (a handheld walk starts tilted). The ground's
/// thickness is measured where the sensor went, which is ground by construction: a handheld map's
/// floor is 0.3-0.5 m thick (range noise, the odometry's drift within the map), a car's road a few
/// centimetres. Points within that thickness are ground, never obstacles.
OccupancyGrid BandOccupancy(const RunFolder& run, const RunState& state, const PipelineConfig& config,
                            const OccupancyProgress& on_map) {
    const OccupancyConfig& o = config.occupancy;
    MapCounter counted{on_map, 2 * state.maps.size()};
    std::optional<Eigen::Isometry3d> T_level_world;  ///< set by the first map, the same in both passes
    const auto measure = [&](const MapRecordSummary& map) {
        const auto points = ReadMapPoints(run, map.id);
        const GroundAlignment ground = AlignGround(points);
        const Eigen::Isometry3d T_ground_map = ground.aligned ? ground.T_ground_map : map.T_ground_map;
        if (!T_level_world) T_level_world = T_ground_map * map.T_world_map_corrected.inverse();
        const Eigen::Isometry3d T_level_map = *T_level_world * map.T_world_map_corrected;
        std::vector<Eigen::Vector3d> levelled(points.size());
        for (std::size_t i = 0; i < points.size(); ++i) levelled[i] = T_ground_map * points[i].cast<double>();
        const LocalGround local(levelled, std::max(o.ground_cell, config.output.map_voxel));
        // The sensor's path in the levelled map frame (the map was built from the odometry poses).
        std::vector<LocalGround::Cell> path;
        for (std::size_t k = map.first_scan; k <= map.last_scan && k < state.odometry.size(); ++k)
            path.push_back(local.Key(T_ground_map * map.T_world_map.inverse() * state.odometry[k].translation()));
        const auto around_path = LocalGround::Around(path);
        MapHeights out;
        out.points.resize(points.size());
        std::vector<double> under_path;
        for (std::size_t i = 0; i < points.size(); ++i) {
            const double height = local.HeightOf(levelled[i]);
            out.points[i] = {Xy(T_level_map * points[i].cast<double>()), height};
            // Below the band's middle: the floor, not the carrier or a ceiling over the path.
            if (height < 0.5 * o.max_height && local.Beside(levelled[i], around_path)) under_path.push_back(height);
        }
        out.ground_thickness = Quantile(under_path, 0.9);
        return out;
    };
    // Two passes as for the lasers: the extent first, so that memory holds one map's points at a time.
    Eigen::AlignedBox2d extent;
    for (const auto& map : state.maps) {
        for (const auto& [xy, height] : measure(map).points)
            if (height <= o.max_height) extent.extend(xy);
        counted.Next();
    }
    const double wanted = o.resolution > 0.0 ? o.resolution : config.output.map_voxel;
    OccupancyGrid grid(extent, FittingResolution(extent, wanted, o.max_cells_per_side));
    for (const auto& map : state.maps) {
        const MapHeights heights = measure(map);
        const double ground = std::max(o.ground_tolerance, heights.ground_thickness);
        const double lowest_obstacle = std::max(o.min_height, ground);
        for (const auto& [xy, height] : heights.points) {
            if (height < ground) {
                grid.AddMiss(xy);
            } else if (height >= lowest_obstacle && height <= o.max_height) {
                grid.AddHit(xy);
            }
        }
        counted.Next();
    }
    return grid;
}

}  // namespace

OccupancyGrid BuildRunOccupancy(const RunFolder& run, const RunState& state, const PipelineConfig& config,
                                const OccupancyProgress& on_map) {
    return config.odometry.planar ? PlanarOccupancy(run, state, config.occupancy, on_map) : BandOccupancy(run, state, config, on_map);
}

fs::path WriteRunOccupancy(const RunFolder& run, const RunState& state, const PipelineConfig& config, const fs::path& image,
                           const OccupancyProgress& on_map) {
    const OccupancyGrid grid = BuildRunOccupancy(run, state, config, on_map);
    fs::path yaml = image;
    yaml.replace_extension(".yaml");
    WriteFileAtomically(image, [&](std::ostream& out) {
        if (image.extension() == ".pgm") WritePgm(out, grid, config.occupancy.occupied_share);
        else WritePng(out, grid, config.occupancy.occupied_share);
    });
    WriteFileAtomically(yaml, [&](std::ostream& out) { WriteMapYaml(out, grid, image.filename().string()); });
    return yaml;
}

}  // namespace revisit
