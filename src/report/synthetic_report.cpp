#include "report/synthetic_report.hpp"

#include "closures/features.hpp"

#include <cmath>
#include <memory>
#include <random>

namespace revisit {
namespace {

/// Surfaces of random boxes off the road: walls sampled every 0.25 m, every 0.4 m in height.
std::vector<Eigen::Vector3f> BoxWorld(const SyntheticRunConfig& config, std::mt19937& rng) {
    std::uniform_real_distribution<double> position(-config.loop_radius - 35.0, config.loop_radius + 35.0);
    std::uniform_real_distribution<double> size(2.0, 9.0), height(3.0, 12.0), yaw(0.0, M_PI);
    std::vector<Eigen::Vector3f> points;
    for (int placed = 0, tries = 0; placed < 160 && tries < 5000; ++tries) {
        const Eigen::Vector2d centre(position(rng), position(rng));
        if (std::abs(centre.norm() - config.loop_radius) < 9.0) continue;  // keep the road free
        ++placed;
        const double sx = size(rng), sy = size(rng), h = height(rng), a = yaw(rng);
        const Eigen::Rotation2Dd R(a);
        const Eigen::Vector2d corners[4] = {{-sx / 2, -sy / 2}, {sx / 2, -sy / 2}, {sx / 2, sy / 2}, {-sx / 2, sy / 2}};
        for (int k = 0; k < 4; ++k) {
            const Eigen::Vector2d a0 = centre + R * corners[k], a1 = centre + R * corners[(k + 1) % 4];
            const int steps = static_cast<int>((a1 - a0).norm() / 0.25);
            for (int s = 0; s < steps; ++s)
                for (double z = 0.0; z < h; z += 0.4) {
                    const Eigen::Vector2d p = a0 + (a1 - a0) * (double(s) / steps);
                    points.emplace_back(float(p.x()), float(p.y()), float(z));
                }
        }
    }
    return points;
}

struct SyntheticWorld {
    SyntheticRunConfig config;
    std::vector<Eigen::Vector3f> points_world;
    std::vector<Eigen::Isometry3d> T_world_true;  ///< per scan
    std::vector<Eigen::Isometry3d> T_world_odom;  ///< per scan

    LocalMap Map(int id) const {
        LocalMap map;
        map.id = id;
        map.first_scan = std::size_t(id) * config.scans_per_map;
        map.last_scan = map.first_scan + config.scans_per_map - 1;
        map.T_world_map = T_world_odom[map.first_scan];
        const Eigen::Isometry3d T_map_world = T_world_true[map.first_scan].inverse();
        const Eigen::Vector3d origin = T_world_true[map.first_scan].translation();
        // Each visit sees a different half of the surfaces with its own noise, like a real revisit.
        std::mt19937 rng(config.seed * 7919u + std::uint32_t(id));
        std::bernoulli_distribution keep(0.5);
        std::normal_distribution<double> noise(0.0, 0.03);
        for (const auto& p : points_world)
            if ((p.cast<double>() - origin).head<2>().norm() < config.map_radius && keep(rng))
                map.points.push_back((T_map_world * (p.cast<double>() + Eigen::Vector3d(noise(rng), noise(rng), 0.0))).cast<float>());
        return map;
    }
};

}  // namespace

ReportInput MakeSyntheticRun(const SyntheticRunConfig& config) {
    std::mt19937 rng(config.seed);
    auto world = std::make_shared<SyntheticWorld>();
    world->config = config;
    world->points_world = BoxWorld(config, rng);
    const int laps = 1 + (config.num_closures + config.maps_per_lap - 1) / config.maps_per_lap;
    const int scans_per_lap = config.maps_per_lap * config.scans_per_map;
    const int num_scans = laps * scans_per_lap;
    ReportInput input;
    input.title = "revisit report (synthetic run)";
    for (int i = 0; i < num_scans; ++i) {
        const double angle = 2.0 * M_PI * i / scans_per_lap;
        Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
        T.translation() << config.loop_radius * std::cos(angle), config.loop_radius * std::sin(angle), 0.0;
        T.linear() = Eigen::AngleAxisd(angle + M_PI / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
        // Odometry: the true pose rotated about the start point by the accumulated heading drift.
        Eigen::Isometry3d drift(Eigen::AngleAxisd(config.yaw_drift * i / scans_per_lap, Eigen::Vector3d::UnitZ()));
        const Eigen::Vector3d start(config.loop_radius, 0.0, 0.0);
        drift.translation() = start - drift.linear() * start;
        world->T_world_true.push_back(T);
        world->T_world_odom.push_back(drift * T);
        const double t = 0.1 * i;
        input.reference.timestamps.push_back(t);
        input.reference.T_world_sensor.push_back(T);
        input.odometry.timestamps.push_back(t);
        input.odometry.T_world_sensor.push_back(drift * T);
        input.corrected.timestamps.push_back(t);
        Eigen::Isometry3d corrected = T;
        corrected.translation().x() += 0.05 * std::sin(0.05 * i);
        input.corrected.T_world_sensor.push_back(corrected);
        input.ape_before.timestamps.push_back(t);
        input.ape_before.values.push_back(((drift * T).translation() - T.translation()).norm());
        input.ape_after.timestamps.push_back(t);
        input.ape_after.values.push_back(std::abs(0.05 * std::sin(0.05 * i)));
    }

    std::uniform_real_distribution<double> unit(0.0, 1.0);
    for (int k = 0; k < config.num_closures; ++k) {
        ClosureEntry entry;
        Closure& c = entry.closure;
        c.ref_id = k % config.maps_per_lap;
        c.query_id = c.ref_id + config.maps_per_lap * (1 + k / config.maps_per_lap);
        c.query_scans = {std::size_t(c.query_id) * config.scans_per_map, std::size_t(c.query_id + 1) * config.scans_per_map - 1};
        c.ref_scans = {std::size_t(c.ref_id) * config.scans_per_map, std::size_t(c.ref_id + 1) * config.scans_per_map - 1};
        const Eigen::Isometry3d T_true =
            world->T_world_true[c.query_scans.first].inverse() * world->T_world_true[c.ref_scans.first];
        c.T_query_ref = T_true.matrix();
        // Matches: keypoints on a grid of metric positions, seen in both maps; the first 70% agree with T_true.
        const double resolution = 0.5;
        for (int m = 0; m < 80; ++m) {
            const Eigen::Vector2d ref_metric(-30.0 + 60.0 * unit(rng), -30.0 + 60.0 * unit(rng));
            const bool inlier = m < 56;
            const Eigen::Vector2d query_metric = inlier ? Eigen::Vector2d((T_true * Eigen::Vector3d(ref_metric.x(), ref_metric.y(), 0)).head<2>())
                                                        : Eigen::Vector2d(-30.0 + 60.0 * unit(rng), -30.0 + 60.0 * unit(rng));
            // Keypoints in pixels of an image whose origin is at -40 m (map_radius) with 0.5 m cells.
            c.ref_keypoints.push_back(((ref_metric.array() + config.map_radius) / resolution).cast<float>());
            c.query_keypoints.push_back(((query_metric.array() + config.map_radius) / resolution).cast<float>());
            c.matches.push_back({m, m, 20 + m % 30});
            c.inlier_mask.push_back(inlier);
        }
        c.num_inliers = 56;
        c.num_votes = 90;
        entry.accepted = unit(rng) >= config.reject_fraction;
        entry.reached_threshold = true;
        entry.verified = entry.accepted;
        entry.reason = entry.accepted ? "ICP fitness above threshold" : "ICP fitness below threshold";
        entry.fitness = entry.accepted ? 0.85 : 0.25;
        entry.rmse = entry.accepted ? 0.08 : 0.6;
        entry.gt_translation_error = 0.1;
        entry.gt_rotation_error = 0.3;
        entry.gt_true_positive = entry.accepted;
        input.closures.push_back(std::move(entry));
    }

    // Weak candidates after the real ones (their own generator: the real ones stay as they were).
    std::mt19937 weak_rng(config.seed + 1000u);
    const int num_maps = laps * config.maps_per_lap;
    std::uniform_int_distribution<int> any_map(0, num_maps - 1), inliers(3, 9), votes(3, 40);
    for (int k = 0; k < config.weak_candidates; ++k) {
        ClosureEntry entry;
        Closure& c = entry.closure;
        c.query_id = any_map(weak_rng);
        c.ref_id = any_map(weak_rng);
        if (c.query_id < c.ref_id) std::swap(c.query_id, c.ref_id);
        c.query_scans = {std::size_t(c.query_id) * config.scans_per_map, std::size_t(c.query_id + 1) * config.scans_per_map - 1};
        c.ref_scans = {std::size_t(c.ref_id) * config.scans_per_map, std::size_t(c.ref_id + 1) * config.scans_per_map - 1};
        c.num_inliers = inliers(weak_rng);
        c.num_votes = votes(weak_rng);
        for (int m = 0; m < 3 * c.num_inliers; ++m) {
            c.query_keypoints.emplace_back(float(160.0 * unit(weak_rng)), float(160.0 * unit(weak_rng)));
            c.ref_keypoints.emplace_back(float(160.0 * unit(weak_rng)), float(160.0 * unit(weak_rng)));
            c.matches.push_back({m, m, 30 + m % 20});
            c.inlier_mask.push_back(m < c.num_inliers);
        }
        c.T_query_ref = Eigen::Isometry3d(Eigen::AngleAxisd(3.0 * unit(weak_rng), Eigen::Vector3d::UnitZ())).matrix();
        entry.reason = "below the acceptance threshold (" + std::to_string(c.num_inliers) + " < 10 inliers)";
        entry.gt_translation_error = 5.0 + 40.0 * unit(weak_rng);
        entry.gt_rotation_error = 180.0 * unit(weak_rng);
        input.closures.push_back(std::move(entry));
    }
    for (int k = 0; k < config.proximity_closures; ++k) {
        ClosureEntry entry;
        Closure& c = entry.closure;
        c.ref_id = config.maps_per_lap - 1 - k % config.maps_per_lap;
        c.query_id = c.ref_id + config.maps_per_lap;
        c.query_scans = {std::size_t(c.query_id) * config.scans_per_map, std::size_t(c.query_id + 1) * config.scans_per_map - 1};
        c.ref_scans = {std::size_t(c.ref_id) * config.scans_per_map, std::size_t(c.ref_id + 1) * config.scans_per_map - 1};
        const Eigen::Isometry3d T_true =
            world->T_world_true[c.query_scans.first].inverse() * world->T_world_true[c.ref_scans.first];
        c.T_query_ref = T_true.matrix();
        entry.proximity = true;
        entry.accepted = entry.reached_threshold = entry.verified = true;
        entry.reason = "graph weight 1.00";
        entry.fitness = 0.7;
        entry.rmse = 0.1;
        entry.T_query_ref_refined = T_true.matrix();
        entry.gt_translation_error = 0.05;
        entry.gt_rotation_error = 0.1;
        entry.gt_true_positive = true;
        input.closures.push_back(std::move(entry));
    }
    input.proximity_registered = std::size_t(config.proximity_closures);
    int true_closures = 0, false_closures = 0;
    for (const auto& entry : input.closures)
        if (entry.accepted) (entry.gt_true_positive.value_or(false) ? true_closures : false_closures) += 1;
    input.true_closures = true_closures;
    input.false_closures = false_closures;

    input.dataset_summary = {"synthetic loop, radius " + std::to_string(int(config.loop_radius)) + " m",
                             std::to_string(num_scans) + " scans, " + std::to_string(laps) + " laps"};
    input.config_text = "maps_per_lap: " + std::to_string(config.maps_per_lap) + "\nseed: " + std::to_string(config.seed) + "\n";
    input.counts = {{"scans", std::to_string(num_scans)}, {"local maps", std::to_string(laps * config.maps_per_lap)},
                    {"closures", std::to_string(config.num_closures + config.weak_candidates)}};
    input.timings = {{"odometry", 12.5}, {"local maps", 3.1}, {"closures", 4.2}, {"refinement", 6.0}, {"pose graph", 0.8}};
    input.metrics = {{"method", "precision", "recall", "F1"}, {{"density-ORB", "0.95", "0.80", "0.869"}}};
    PrCurve curve{"density-ORB", {}, std::nullopt};
    for (int i = 0; i <= 20; ++i) {
        const double r = i / 20.0;
        curve.points.push_back({double(i), 1.0 - 0.6 * r * r * r, r});
    }
    input.pr_curves = {curve, PrCurve{"scan context", {{0, 0.9, 0.1}, {1, 0.8, 0.5}, {2, 0.5, 0.9}}, std::nullopt}};
    input.load_local_map = [world](int id) -> std::optional<LocalMap> {
        if (id < 0 || std::size_t(id + 1) * world->config.scans_per_map > world->T_world_true.size()) return std::nullopt;
        return world->Map(id);
    };
    input.load_density_image = [world](int id) -> std::optional<DensityImage> {
        if (id < 0 || std::size_t(id + 1) * world->config.scans_per_map > world->T_world_true.size()) return std::nullopt;
        // Fixed 80 m x 80 m frame so the synthetic keypoints land on it: origin at -map_radius.
        auto map = world->Map(id);
        map.points.push_back(Eigen::Vector3f(-world->config.map_radius, -world->config.map_radius, 0.f));
        map.points.push_back(Eigen::Vector3f(world->config.map_radius, world->config.map_radius, 0.f));
        return ComputeDensityImage(map.points);
    };
    for (int id = 0; id < num_maps; ++id) {
        input.map_ids.push_back(id);
        input.map_scans.push_back({std::size_t(id) * config.scans_per_map, std::size_t(id + 1) * config.scans_per_map - 1});
    }
    input.load_keypoints = [density = input.load_density_image](int id) {
        const auto image = density(id);
        return image ? ComputeFeatures(image->image).keypoints : std::vector<Eigen::Vector2f>{};
    };
    input.load_global_map = [world] { return world->points_world; };
    return input;
}

}  // namespace revisit
