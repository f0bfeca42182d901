#include "sim/sensor.hpp"

#include <cmath>
#include <cstdint>

#include "sim/counter_random.hpp"

namespace revisit {
namespace {

constexpr double kPi = 3.14159265358979323846;
double Radians(double degrees) { return degrees * kPi / 180.0; }

Eigen::Vector3d FromAngles(double azimuth, double elevation) {
    return {std::cos(elevation) * std::cos(azimuth), std::cos(elevation) * std::sin(azimuth), std::sin(elevation)};
}

/// Deterministic draw in [-1, 1) from a key (counter-based: no state shared between beams or sweeps).
double Signed(std::uint64_t key) { return 2.0 * UnitFromKey(key) - 1.0; }

/// Approximately normal (sum of three uniforms, variance 1) for beam `beam`, quantity `what`.
double BeamNormal(std::size_t beam, std::uint64_t what) {
    const std::uint64_t key = (static_cast<std::uint64_t>(beam) << 8) ^ (what * 0xD1B54A32D192ED03ULL);
    return Signed(key) + Signed(key ^ 0x1111) + Signed(key ^ 0x2222);
}

/// Calibration residuals of a factory-calibrated spinning unit (HDL-64E: per-laser corrections are
/// given to ~0.1 deg and ~2 cm; the firing azimuths are not locked to the revolution).
void SpinningImperfections(SensorConfig& config) {
    config.beam_elevation_sigma = Radians(0.05);
    config.beam_azimuth_sigma = Radians(0.05);
    config.beam_range_sigma = 0.015;
    config.azimuth_jitter = true;
}

/// An Ouster-like head: 128 beams evenly over +-`half_fov_deg`, 3 cm range noise.
SensorConfig Ouster128(const std::string& label, double half_fov_deg, int azimuth_steps, double min_range, double max_range) {
    SensorConfig config;
    config.label = label;
    for (int i = 0; i < 128; ++i) config.vertical_angles.push_back(Radians(half_fov_deg - 2.0 * half_fov_deg * i / 127.0));
    config.azimuth_steps = azimuth_steps;
    SpinningImperfections(config);
    config.min_range = min_range;
    config.max_range = max_range;
    config.range_noise = 0.03;
    return config;
}

}  // namespace

std::size_t SensorConfig::NumRays() const {
    switch (type) {
        case SensorType::kSpinning: return vertical_angles.size() * static_cast<std::size_t>(azimuth_steps);
        case SensorType::kRosette: return static_cast<std::size_t>(rosette_points);
        case SensorType::kPlanar: return static_cast<std::size_t>(planar_beams);
        case SensorType::kDepthCamera: return static_cast<std::size_t>(image_width) * image_height;
    }
    return 0;
}

SensorConfig Hdl64Sensor() {
    SensorConfig config;
    config.label = "VELODYNE";
    // Upper block: 32 beams from +2.0 down by 1/3 degree; lower block: 32 beams from -8.83 down by 1/2 degree.
    for (int i = 0; i < 32; ++i) config.vertical_angles.push_back(Radians(2.0 - i / 3.0));
    for (int i = 0; i < 32; ++i) config.vertical_angles.push_back(Radians(-8.83 - 0.5 * i));
    config.azimuth_steps = 2048;
    SpinningImperfections(config);
    config.min_range = 2.5;
    config.max_range = 120.0;
    return config;
}

SensorConfig Vlp16Sensor() {
    SensorConfig config;
    config.label = "VLP16";
    for (int i = 0; i < 16; ++i) config.vertical_angles.push_back(Radians(15.0 - 2.0 * i));
    config.azimuth_steps = 1800;
    SpinningImperfections(config);
    config.min_range = 1.0;
    config.max_range = 100.0;
    config.range_noise = 0.03;
    return config;
}

SensorConfig Os128Sensor() { return Ouster128("OS128", 22.5, 1024, 1.0, 120.0); }

// min_range 0.3 m: it sees the person carrying it, which the odometry's crop must drop.
SensorConfig Os0Sensor() { return Ouster128("OS0", 45.0, 512, 0.3, 50.0); }

SensorConfig LivoxAviaSensor() {
    SensorConfig config;
    config.type = SensorType::kRosette;
    config.label = "LIVOX";
    config.rosette_points = 24000;
    config.min_range = 1.0;
    config.max_range = 190.0;
    config.range_noise = 0.02;
    return config;
}

SensorConfig PlanarLaserSensor(double aperture_deg) {
    SensorConfig config;
    config.type = SensorType::kPlanar;
    config.label = "LASER";
    config.rate = 10.0;
    config.planar_aperture = Radians(aperture_deg);
    config.planar_beams = aperture_deg >= 359.0 ? 720 : 361;
    config.min_range = 0.1;
    config.max_range = 30.0;
    config.range_noise = 0.01;
    config.dropout = 0.01;
    return config;
}

SensorConfig DepthCameraSensor() {
    SensorConfig config;
    config.type = SensorType::kDepthCamera;
    config.label = "DEPTH";
    config.rate = 30.0;
    config.min_range = 0.3;
    config.max_range = 8.0;
    config.range_noise = 0.0012;
    config.range_noise_quadratic = 0.0019;
    config.dropout = 0.02;
    return config;
}

std::vector<SensorRay> MakeRays(const SensorConfig& config, std::size_t sweep_index) {
    std::vector<SensorRay> rays;
    rays.reserve(config.NumRays());
    const double period = 1.0 / config.rate;
    switch (config.type) {
        case SensorType::kSpinning: {
            // Firing order: all beams at one azimuth, azimuth sweeping counter-clockwise from the back.
            const std::size_t beams = config.vertical_angles.size();
            std::vector<double> d_elevation(beams, 0.0), d_azimuth(beams, 0.0), d_range(beams, 0.0);
            for (std::size_t b = 0; b < beams; ++b) {
                d_elevation[b] = config.beam_elevation_sigma * BeamNormal(b, 1);
                d_azimuth[b] = config.beam_azimuth_sigma * BeamNormal(b, 2);
                d_range[b] = config.beam_range_sigma * BeamNormal(b, 3);
            }
            const double phase = config.azimuth_jitter ? 0.5 * (1.0 + Signed(0xA5A5A5A5ULL + sweep_index)) : 0.0;
            for (int a = 0; a < config.azimuth_steps; ++a) {
                const double f = (a + phase) / config.azimuth_steps;
                const double azimuth = -kPi + 2.0 * kPi * f;
                for (std::size_t b = 0; b < beams; ++b)
                    rays.push_back({FromAngles(azimuth + d_azimuth[b], config.vertical_angles[b] + d_elevation[b]),
                                    f * period, d_range[b]});
            }
            break;
        }
        case SensorType::kRosette: {
            // Two counter-rotating prisms with incommensurate rates: petals that never repeat exactly.
            const double w1 = 2.0 * kPi * 1733.7, w2 = 2.0 * kPi * 1212.1;  // [rad/s]
            for (int k = 0; k < config.rosette_points; ++k) {
                const double f = static_cast<double>(k) / config.rosette_points;
                const double tau = (static_cast<double>(sweep_index) + f) * period;
                const double u = 0.5 * (std::cos(w1 * tau) + std::cos(w2 * tau));
                const double v = 0.5 * (std::sin(w1 * tau) - std::sin(w2 * tau));
                const Eigen::Vector3d d(1.0, std::tan(config.rosette_half_fov_h * u), std::tan(config.rosette_half_fov_v * v));
                rays.push_back({d.normalized(), f * period});
            }
            break;
        }
        case SensorType::kPlanar: {
            // Beam i at -aperture/2 + i * aperture / (n - 1) (full circles: n beams without the repeated end).
            const bool full = config.planar_aperture >= 2.0 * kPi - 1e-6;
            const int n = config.planar_beams;
            const double step = full ? config.planar_aperture / n : config.planar_aperture / std::max(1, n - 1);
            for (int i = 0; i < n; ++i)
                rays.push_back({FromAngles(-0.5 * config.planar_aperture + i * step, 0.0), period * i / n});
            break;
        }
        case SensorType::kDepthCamera: {
            const double cx = 0.5 * (config.image_width - 1), cy = 0.5 * (config.image_height - 1);
            for (int r = 0; r < config.image_height; ++r)
                for (int c = 0; c < config.image_width; ++c)
                    rays.push_back({Eigen::Vector3d(1.0, -(c - cx) / config.focal_length, -(r - cy) / config.focal_length)
                                        .normalized(),
                                    0.0});
            break;
        }
    }
    return rays;
}

}  // namespace revisit
