#pragma once
/// The simulator's entry points: a world, a route through it, a sensor; scans written to a dataset.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>

#include "io/writer.hpp"
#include "sim/generators.hpp"
#include "sim/odometry_noise.hpp"
#include "sim/ray_caster.hpp"
#include "sim/revisits.hpp"
#include "sim/route.hpp"
#include "sim/sensor.hpp"

namespace revisit {

enum class WorldKind { kCity, kHighway, kIndoor, kAroundTrajectory };

struct SimConfig {
    std::string name = "custom";       ///< preset name, written to sim.yaml
    std::uint64_t seed = 1;            ///< every random choice derives from it
    WorldKind world = WorldKind::kCity;
    CityConfig city;
    HighwayConfig highway;
    IndoorConfig indoor;
    AroundTrajectoryConfig around;
    std::filesystem::path trajectory_file;  ///< kAroundTrajectory: KITTI or TUM poses to follow
    RouteConfig route;
    MotionConfig motion;
    SensorConfig sensor;
    OdometryNoiseConfig odometry;
    bool moving_cars = true;
    std::size_t max_scans = 0;         ///< 0: the whole route
    /// Another session in the same world (issue 20): 0 is the preset's route; K > 0 keeps the world
    /// (its seed) and draws the route, the drive, the sensor noise and the odometry from SessionSeed.
    int session = 0;
};

/// The seed of everything but the world: `seed` for session 0, another per session.
std::uint64_t SessionSeed(const SimConfig& config);

/// World, trajectory and revisits of a configuration, before any ray is cast.
struct SimPlan {
    World world;
    Trajectory trajectory;             ///< T_world_sensor at the scan time stamps
    Poses odometry;                    ///< drifting prior, empty when disabled
    std::vector<Revisit> revisits;     ///< found in `trajectory` with RevisitConfig defaults
};

struct SimSummary {
    std::size_t scans = 0;
    std::size_t points = 0;
    double length = 0.0;               ///< [m]
    double duration = 0.0;             ///< [s] of simulated time
    std::size_t primitives = 0;
    std::size_t revisits = 0;
    std::size_t opposite_revisits = 0;
};

using SimProgress = std::function<void(std::size_t done, std::size_t total)>;

/// Builds the world and plans the route (reads `trajectory_file` for kAroundTrajectory).
SimPlan PlanSimulation(const SimConfig& config);
/// The sweeps of a plan one at a time (what SimulateSequence writes and `sim:` datasets read). Holds
/// references: `config` and `plan` outlive it.
class PlanSweeps {
  public:
    PlanSweeps(const SimConfig& config, const SimPlan& plan);
    /// Sweep k of the plan (reference pose, time stamp, points in the sensor frame); no odometry prior.
    Scan Simulate(const RayCaster& caster, std::size_t k) const;

  private:
    const SimConfig& config_;
    const SimPlan& plan_;
    bool fixed_pattern_;
    std::vector<SensorRay> rays_;  ///< the rays of every sweep when the pattern is fixed
};

/// Simulates every scan of the plan and hands it to `writer` (then calls Finish()).
SimSummary SimulateSequence(const SimConfig& config, DatasetWriter& writer, const SimProgress& progress = {});
/// `revisit simulate`: KITTI folder (or a rawlog when `out` ends in .rawlog/.rawlog.gz) plus sim.yaml
/// with the preset, seed and parameters (next to a rawlog: <out>.sim.yaml).
SimSummary RunSimulation(const SimConfig& config, const std::filesystem::path& out, bool force,
                         const SimProgress& progress = {});

/// The parameters as YAML text (hand-written: the core library does not link yaml-cpp).
std::string SimConfigYaml(const SimConfig& config, const SimSummary& summary);

}  // namespace revisit
