#pragma once
/// Range sensor models: beam patterns, range limits, noise, dropouts and sweep timing.
#include <Eigen/Core>
#include <cstddef>
#include <string>
#include <vector>

namespace revisit {

enum class SensorType { kSpinning, kRosette, kPlanar, kDepthCamera };

struct SensorConfig {
    SensorType type = SensorType::kSpinning;
    std::string label = "VELODYNE";
    double rate = 10.0;                       ///< [Hz] sweeps per second
    double min_range = 2.5;                   ///< [m] returns closer than this are dropped
    double max_range = 120.0;                 ///< [m]
    double range_noise = 0.02;                ///< [m] Gaussian range sigma, constant part ...
    double range_noise_quadratic = 0.0;       ///< [1/m] ... plus this times range^2 (depth cameras)
    double dropout = 0.03;                    ///< probability that a return is lost
    double intensity_noise = 0.03;            ///< sigma of the intensity [0..1]
    bool motion_distortion = false;           ///< rays leave from the pose at their own time in the sweep
    // A real unit's imperfections (issue 15): every beam is off by a fixed calibration residual, and a
    // spinning head does not fire at the same azimuths in every sweep. Without them each ray of a
    // stationary sensor hits exactly the same spot sweep after sweep.
    double beam_elevation_sigma = 0.0;        ///< [rad] per-beam elevation offset, fixed for the unit
    double beam_azimuth_sigma = 0.0;          ///< [rad] per-beam azimuth offset, fixed for the unit
    double beam_range_sigma = 0.0;            ///< [m] per-beam range offset, fixed for the unit
    bool azimuth_jitter = false;              ///< spinning: each sweep starts at a random fraction of an azimuth step

    // Spinning LiDAR.
    std::vector<double> vertical_angles;      ///< [rad] elevation of each beam (ring), top first
    int azimuth_steps = 2048;                 ///< firings per revolution
    // Livox-like rosette.
    int rosette_points = 24000;               ///< points per sweep
    double rosette_half_fov_h = 0.614;        ///< [rad] (70.4 deg total)
    double rosette_half_fov_v = 0.674;        ///< [rad] (77.2 deg total)
    // Planar 2D laser.
    double planar_aperture = 3.14159265358979323846;  ///< [rad] centred on +x
    int planar_beams = 361;
    // Depth camera (x forward; pixel rows go down, columns go right).
    int image_width = 640;
    int image_height = 480;
    double focal_length = 525.0;              ///< [px]

    std::size_t NumRays() const;
};

/// HDL-64E-like: +2 to -24.9 degrees, 1/3 degree spacing in the upper block, 1/2 in the lower.
SensorConfig Hdl64Sensor();
/// VLP-16-like: +-15 degrees, 2 degree spacing, 100 m.
SensorConfig Vlp16Sensor();
/// OS1-128-like: +-22.5 degrees, 128 beams.
SensorConfig Os128Sensor();
/// OS0-128-like wide-angle short-range head: +-45 degrees, 128 beams, 512 azimuths (its 512x10 mode), 0.3-50 m.
SensorConfig Os0Sensor();
/// Livox-Avia-like non-repetitive rosette, 70.4 x 77.2 degree field of view.
SensorConfig LivoxAviaSensor();
/// 2D laser scanner: 180 degrees (361 beams) or 360 degrees (720 beams), 30 m.
SensorConfig PlanarLaserSensor(double aperture_deg);
/// Depth camera: 640 x 480 pinhole, 0.3-8 m, depth-dependent noise.
SensorConfig DepthCameraSensor();

struct SensorRay {
    Eigen::Vector3d direction;  ///< unit, in the sensor frame (x forward, y left, z up)
    double time = 0.0;          ///< [s] from the start of the sweep
    double range_offset = 0.0;  ///< [m] the beam's calibration residual, added to the measured range
};

/// The rays of sweep `sweep_index`. The rosette's pattern keeps evolving from sweep to sweep; a spinning
/// head's azimuths shift by a fraction of a step when `azimuth_jitter` is on.
std::vector<SensorRay> MakeRays(const SensorConfig& config, std::size_t sweep_index);

}  // namespace revisit
