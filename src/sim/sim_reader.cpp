#include "sim/sim_reader.hpp"

#include "core/error.hpp"
#include "io/trajectory_io.hpp"
#include "sim/presets.hpp"
#include "sim/ray_caster.hpp"

#include <algorithm>
#include <exception>
#include <string>

namespace revisit {
namespace {

constexpr const char* kScheme = "sim:";

class SimulationReader final : public Reader {
  public:
    SimulationReader(const SimConfig& config, const std::string& name, const ReaderOptions& options)
        : config_(WrittenConfig(config)), plan_(PlanSimulation(config_)), caster_(plan_.world), sweeps_(config_, plan_) {
        // The caster keeps its own prepared copy of the boxes, and nothing else reads the world's: on a
        // long route they are tens of MB held beside the chain's growing memory until the last scan.
        std::vector<OrientedBox>().swap(plan_.world.boxes);
        plan_.trajectory.poses.shrink_to_fit();
        plan_.trajectory.timestamps.shrink_to_fit();
        info_.format = "sim";
        info_.path = name;
        info_.num_scans = plan_.trajectory.size();
        info_.has_reference_poses = true;
        if (!options.poses_file.empty()) {
            // As for a folder: another reference, one pose per scan.
            Trajectory given = ReadPoses(options.poses_file);
            if (given.size() != plan_.trajectory.size()) {
                throw DatasetError(options.poses_file, std::to_string(given.size()) + " poses for " +
                                                           std::to_string(plan_.trajectory.size()) + " scans");
            }
            reference_ = std::move(given.poses);
            info_.poses_file = options.poses_file;
        }
    }

    std::optional<Scan> Next() override {
        if (next_ >= plan_.trajectory.size()) return std::nullopt;
        const std::size_t k = next_++;
        Scan scan = sweeps_.Simulate(caster_, k);
        // What the KITTI folder keeps of the sweep (io/writer.hpp): float32 x y z i, a time, a reference.
        scan.point_times.clear();
        scan.T_odom_sensor.reset();
        scan.planar_beams.reset();
        if (!scan.has_intensities()) scan.intensities.assign(scan.points.size(), 0.f);
        scan.sensor_label = "VELODYNE";
        // poses.txt and times.txt keep 9 decimals: the same values as the folder, to the bit.
        scan.timestamp = AsStoredTime(scan.timestamp);
        if (scan.T_world_sensor) scan.T_world_sensor = AsStoredKittiPose(*scan.T_world_sensor);
        if (!reference_.empty()) scan.T_world_sensor = reference_[k];
        stats_.scans++;
        stats_.points += scan.points.size();
        return scan;
    }

    /// Each scan is ray-cast from its own pose and seed (PlanSweeps::Simulate): any scan can come first.
    bool SkipTo(std::size_t index) override {
        const std::size_t to = std::min(index, plan_.trajectory.size());
        if (to > next_) {
            stats_.scans += to - next_;
            next_ = to;
        }
        return true;
    }

    const DatasetInfo& Info() const override { return info_; }

  private:
    /// The sweeps `revisit simulate` writes: undistorted, since the written formats have no per-point
    /// times (sim/simulate.cpp, RunSimulation).
    static SimConfig WrittenConfig(SimConfig config) {
        config.sensor.motion_distortion = false;
        // A KITTI folder has no odometry prior, so the plan needs none: on a long route the drifting
        // prior is a pose per scan (tens of MB at 100,000 scans) no scan would carry.
        config.odometry.enabled = false;
        return config;
    }

    SimConfig config_;
    SimPlan plan_;
    RayCaster caster_;
    PlanSweeps sweeps_;
    Poses reference_;
    DatasetInfo info_;
    std::size_t next_ = 0;
};

}  // namespace

std::unique_ptr<Reader> OpenSimulation(const SimConfig& config, const std::string& name) {
    return std::make_unique<SimulationReader>(config, name, ReaderOptions{});
}

SimConfig SimConfigFromSpec(const std::string& spec) {
    std::string preset = spec.rfind(kScheme, 0) == 0 ? spec.substr(4) : spec;
    std::string length_text;
    if (const auto comma = preset.find(','); comma != std::string::npos) {
        const std::string option = preset.substr(comma + 1);
        preset.resize(comma);
        if (option.rfind("length=", 0) != 0)
            throw DatasetError(spec, "unknown simulator option '" + option + "' (known: length=METRES)");
        length_text = option.substr(7);
    }
    try {
        SimConfig config = SimPreset(preset);
        if (!length_text.empty()) {
            std::size_t used = 0;
            double length = 0.0;
            try {
                length = std::stod(length_text, &used);
            } catch (const std::exception&) {
                used = 0;
            }
            if (used == 0 || used != length_text.size())
                throw ConfigError("length '" + length_text + "' is not a number of metres");
            config = WithRouteLength(config, length);
        }
        return config;
    } catch (const ConfigError& error) {
        throw DatasetError(spec, error.what());
    }
}

void RegisterSimulatorDatasets() {
    RegisterDatasetScheme("sim", [](const std::string& spec, const ReaderOptions& options) -> std::unique_ptr<Reader> {
        return std::make_unique<SimulationReader>(SimConfigFromSpec(spec), spec, options);
    });
}

}  // namespace revisit
