#include "sim/simulate.hpp"

#include <tbb/task_group.h>

#include <fstream>
#include <sstream>

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "io/trajectory_io.hpp"
#include "sim/scan_simulator.hpp"

namespace revisit {
namespace {

const char* WorldName(WorldKind kind) {
    switch (kind) {
        case WorldKind::kCity: return "city";
        case WorldKind::kHighway: return "highway";
        case WorldKind::kIndoor: return "indoor";
        case WorldKind::kAroundTrajectory: return "around_trajectory";
    }
    return "unknown";
}

const char* SensorName(SensorType type) {
    switch (type) {
        case SensorType::kSpinning: return "spinning";
        case SensorType::kRosette: return "rosette";
        case SensorType::kPlanar: return "planar";
        case SensorType::kDepthCamera: return "depth_camera";
    }
    return "unknown";
}

/// Revisit detection scaled to the scene: indoor and handheld loops are short.
RevisitConfig RevisitsFor(const SimConfig& config) {
    RevisitConfig revisit;
    if (config.world == WorldKind::kIndoor || config.motion.handheld) {
        revisit.radius = 3.0;
        revisit.min_gap = 30.0;
        revisit.min_length = 5.0;
    }
    return revisit;
}

}  // namespace

std::uint64_t SessionSeed(const SimConfig& config) {
    return config.session == 0 ? config.seed : config.seed + 1000003ULL * static_cast<std::uint64_t>(config.session);
}

SimPlan PlanSimulation(const SimConfig& config) {
    SimPlan plan;
    std::vector<Eigen::Vector2d> path;
    switch (config.world) {
        case WorldKind::kCity: plan.world = GenerateCity(config.city, config.seed); break;
        case WorldKind::kHighway: plan.world = GenerateHighway(config.highway, config.seed); break;
        case WorldKind::kIndoor: plan.world = GenerateIndoor(config.indoor, config.seed); break;
        case WorldKind::kAroundTrajectory: {
            if (config.trajectory_file.empty()) throw ConfigError("sim.trajectory_file: required for an around_trajectory world");
            const Trajectory given = ReadPoses(config.trajectory_file);
            plan.world = GenerateAroundTrajectory(given.poses, config.around, config.seed);
            path = RoutePath(plan.world.streets, {0, 1}, 0.0, 2.0);
            break;
        }
    }
    if (!config.moving_cars) plan.world.moving_cars.clear();
    if (path.empty()) {
        const auto nodes = PlanRoute(plan.world.streets, config.route, SessionSeed(config));
        path = RoutePath(plan.world.streets, nodes, plan.world.lane_offset, config.route.corner_radius);
    }
    MotionConfig motion = config.motion;
    motion.rate = config.sensor.rate;  // one pose per sweep: the sweep start is the previous pose
    plan.trajectory = DrivePath(path, plan.world.ground, motion, SessionSeed(config));
    if (config.max_scans > 0 && plan.trajectory.size() > config.max_scans) {
        plan.trajectory.poses.resize(config.max_scans);
        plan.trajectory.timestamps.resize(config.max_scans);
    }
    if (config.odometry.enabled) plan.odometry = SimulateOdometry(plan.trajectory, config.odometry, SessionSeed(config));
    plan.revisits = FindRevisits(plan.trajectory.poses, RevisitsFor(config));
    return plan;
}

PlanSweeps::PlanSweeps(const SimConfig& config, const SimPlan& plan)
    : config_(config), plan_(plan), fixed_pattern_(config.sensor.type != SensorType::kRosette && !config.sensor.azimuth_jitter) {
    if (fixed_pattern_) rays_ = MakeRays(config.sensor, 0);
}

Scan PlanSweeps::Simulate(const RayCaster& caster, std::size_t k) const {
    const std::vector<SensorRay> rays_of_k = fixed_pattern_ ? std::vector<SensorRay>{} : MakeRays(config_.sensor, k);
    const std::vector<SensorRay>& rays = fixed_pattern_ ? rays_ : rays_of_k;
    SweepInput sweep;
    sweep.index = k;
    sweep.timestamp = plan_.trajectory.timestamps[k];
    sweep.T_world_sensor = plan_.trajectory.poses[k];
    sweep.T_world_sensor_start = plan_.trajectory.poses[k > 0 ? k - 1 : 0];
    const Eigen::Vector2d here = sweep.T_world_sensor.translation().head<2>();
    for (const auto& car : plan_.world.moving_cars) {
        OrientedBox box = car.BoxAt(sweep.timestamp, plan_.world.ground);
        if ((box.center - here).norm() < config_.sensor.max_range + 5.0) sweep.dynamic_boxes.push_back(box);
    }
    return SimulateScan(caster, config_.sensor, rays, sweep, SessionSeed(config_));
}

SimSummary SimulateSequence(const SimConfig& config, DatasetWriter& writer, const SimProgress& progress) {
    const SimPlan plan = PlanSimulation(config);
    const RayCaster caster(plan.world);
    SimSummary summary;
    summary.scans = plan.trajectory.size();
    summary.length = PathLength(plan.trajectory.poses);
    summary.duration = plan.trajectory.has_timestamps() ? plan.trajectory.timestamps.back() : 0.0;
    summary.primitives = plan.world.NumPrimitives();
    summary.revisits = plan.revisits.size();
    for (const auto& r : plan.revisits) summary.opposite_revisits += r.opposite ? 1 : 0;
    const PlanSweeps sweeps(config, plan);
    tbb::task_group writing;
    Scan pending;
    struct WaitOnExit {  // a task_group must not be destroyed with a write in flight (exceptions)
        tbb::task_group& group;
        ~WaitOnExit() {
            try {
                group.wait();
            } catch (...) {
            }
        }
    } wait_on_exit{writing};
    for (std::size_t k = 0; k < plan.trajectory.size(); ++k) {
        Scan scan = sweeps.Simulate(caster, k);
        if (!plan.odometry.empty()) scan.T_odom_sensor = plan.odometry[k];
        summary.points += scan.points.size();
        // Write scan k while scan k+1 is cast: one write in flight, files still written in order.
        writing.wait();
        if (progress && k > 0) progress(k, plan.trajectory.size());
        pending = std::move(scan);
        writing.run([&writer, &pending] { writer.Write(pending); });
    }
    writing.wait();
    if (progress && !plan.trajectory.empty()) progress(plan.trajectory.size(), plan.trajectory.size());
    writer.Finish();
    return summary;
}

std::string SimConfigYaml(const SimConfig& config, const SimSummary& summary) {
    std::ostringstream out;
    out.precision(10);
    const auto& s = config.sensor;
    out << "# revisit simulate: everything needed to regenerate this sequence\n"
        << "preset: " << config.name << "\n"
        << "seed: " << config.seed << "\n"
        << "session: " << config.session << "\n"
        << "world: " << WorldName(config.world) << "\n";
    if (config.world == WorldKind::kCity)
        out << "city: {blocks_x: " << config.city.blocks_x << ", blocks_y: " << config.city.blocks_y
            << ", block_size: " << config.city.block_size << ", road_half_width: " << config.city.road_half_width
            << ", min_building_height: " << config.city.min_building_height
            << ", max_building_height: " << config.city.max_building_height << ", moving_cars: " << config.city.moving_cars
            << (config.city.outer_frontage ? ", outer_frontage: true" : "") << "}\n";
    if (config.world == WorldKind::kHighway)
        out << "highway: {ring_radius: " << config.highway.ring_radius << ", road_half_width: " << config.highway.road_half_width
            << ", bank_probability: " << config.highway.bank_probability << ", bank_height: " << config.highway.bank_height
            << ", tree_belt_probability: " << config.highway.tree_belt_probability
            << ", overpass_spacing: " << config.highway.overpass_spacing << "}\n";
    if (config.world == WorldKind::kIndoor)
        out << "indoor: {rooms_x: " << config.indoor.rooms_x << ", rooms_y: " << config.indoor.rooms_y
            << ", room_size: " << config.indoor.room_size << "}\n";
    if (config.world == WorldKind::kAroundTrajectory)
        out << "trajectory_file: \"" << config.trajectory_file.string() << "\"\n"
            << "around: {clearance: " << config.around.clearance << ", near_clearance: " << config.around.near_clearance
            << ", parking_offset: " << config.around.parking_offset << "}\n";
    // Realism of the worlds (issue 15): ground relief and roughness, foliage, roadside clutter.
    const CityConfig& city = config.world == WorldKind::kAroundTrajectory ? config.around.city : config.city;
    if (config.world == WorldKind::kCity || config.world == WorldKind::kAroundTrajectory)
        out << "surfaces: {ground_relief: " << city.ground_relief << ", ground_roughness: " << city.ground_roughness
            << ", foliage_free_path: " << city.foliage_free_path << ", bush_spacing: " << city.bush_spacing << "}\n";
    if (config.world == WorldKind::kHighway)
        out << "surfaces: {ground_relief: " << config.highway.ground_relief
            << ", ground_roughness: " << config.highway.ground_roughness
            << ", foliage_free_path: " << config.highway.foliage_free_path
            << ", bush_spacing: " << config.highway.bush_spacing << ", rail_post_spacing: " << config.highway.rail_post_spacing
            << "}\n";
    out << "route: {length: " << config.route.length << ", revisits: " << config.route.revisits
        << ", opposite_fraction: " << config.route.opposite_fraction << ", min_revisit_gap: " << config.route.min_revisit_gap
        << "}\n"
        << "motion: {rate: " << config.sensor.rate << ", cruise_speed: " << config.motion.cruise_speed
        << ", mount_height: " << config.motion.mount_height << ", mount_pitch: " << config.motion.mount_pitch
        << ", handheld: " << (config.motion.handheld ? "true" : "false") << "}\n"
        << "sensor: {type: " << SensorName(s.type) << ", label: " << s.label << ", rate: " << s.rate
        << ", beams: " << s.vertical_angles.size() << ", azimuth_steps: " << s.azimuth_steps
        << ", min_range: " << s.min_range << ", max_range: " << s.max_range << ", range_noise: " << s.range_noise
        << ", dropout: " << s.dropout << ", motion_distortion: " << (s.motion_distortion ? "true" : "false")
        << ", beam_elevation_sigma: " << s.beam_elevation_sigma << ", beam_azimuth_sigma: " << s.beam_azimuth_sigma
        << ", beam_range_sigma: " << s.beam_range_sigma << ", azimuth_jitter: " << (s.azimuth_jitter ? "true" : "false")
        << "}\n"
        << "odometry_noise: {enabled: " << (config.odometry.enabled ? "true" : "false")
        << ", speed_scale_bias: " << config.odometry.speed_scale_bias << ", yaw_rate_bias: " << config.odometry.yaw_rate_bias
        << ", yaw_bias_random_walk: " << config.odometry.yaw_bias_random_walk << "}\n"
        << "summary: {scans: " << summary.scans << ", points: " << summary.points << ", length_m: " << summary.length
        << ", duration_s: " << summary.duration << ", primitives: " << summary.primitives
        << ", revisits: " << summary.revisits << ", opposite_revisits: " << summary.opposite_revisits << "}\n";
    return out.str();
}

SimSummary RunSimulation(const SimConfig& config, const std::filesystem::path& out, bool force,
                         const SimProgress& progress) {
    WriterOptions options;
    if (config.sensor.type == SensorType::kPlanar) {
        options.planar_as_range_scan = true;
        options.planar_beams = config.sensor.planar_beams;
        options.planar_aperture = config.sensor.planar_aperture;
        options.planar_max_range = config.sensor.max_range;
    }
    options.write_odometry = config.odometry.enabled;
    // Neither written format has a field for per-point times (KITTI .bin: x y z intensity; the rawlog's
    // point clouds: XYZI), and without them a distorted sweep cannot be undone (a rosette's firing order
    // is not in its geometry): real recordings without times come deskewed, like the keyframes of
    // ../shared/data/livox_handheld_walk. Written sweeps are therefore undistorted (src/sim/README.md:
    // "The handheld walk"); SimulateScan keeps the distortion and its times for callers in memory.
    SimConfig written = config;
    written.sensor.motion_distortion = false;
    auto writer = CreateWriter(out, options, force);
    const SimSummary summary = SimulateSequence(written, *writer, progress);
    const auto yaml = HasRawlogExtension(out) ? std::filesystem::path(out.string() + ".sim.yaml") : out / "sim.yaml";
    std::string text = SimConfigYaml(written, summary);
    if (config.sensor.motion_distortion)
        text = "# the preset's motion distortion is off: the written format carries no per-point times\n" + text;
    WriteFileAtomically(yaml, text);
    return summary;
}

}  // namespace revisit
