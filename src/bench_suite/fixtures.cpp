#include "bench_suite/fixtures.hpp"

#include <cmath>

#include "io/reader.hpp"
#include "sim/presets.hpp"

namespace revisit {

namespace {
/// Keeps every simulated scan in memory instead of writing files.
class CollectingWriter : public DatasetWriter {
  public:
    explicit CollectingWriter(std::vector<Scan>& scans) : scans_(scans) {}
    void Write(const Scan& scan) override { scans_.push_back(scan); }
    void Finish() override {}

  private:
    std::vector<Scan>& scans_;
};
}  // namespace

std::vector<Scan> SimulatedScans(const std::string& preset, std::size_t max_scans, std::uint64_t seed) {
    SimConfig config = SimPreset(preset);
    config.seed = seed;
    config.max_scans = max_scans;
    std::vector<Scan> scans;
    CollectingWriter writer(scans);
    SimulateSequence(config, writer);
    return scans;
}

std::vector<Scan> DatasetScans(const std::filesystem::path& path, std::size_t max_scans, double laser_aperture,
                               std::size_t first) {
    std::vector<Scan> scans;
    if (!std::filesystem::exists(path)) return scans;
    ReaderOptions options;
    options.laser_aperture = laser_aperture;
    auto reader = OpenDataset(path, options);
    for (std::size_t read = 0; scans.size() < max_scans; ++read) {
        auto scan = reader->Next();
        if (!scan) break;
        if (read >= first) scans.push_back(std::move(*scan));
    }
    return scans;
}

LocalMap AccumulateMap(const std::vector<Scan>& scans, std::size_t first, std::size_t last, int id) {
    LocalMapConfig config;
    config.split_distance = 1e9;  // one map for the whole range
    LocalMapper mapper(config);
    for (std::size_t i = first; i <= last && i < scans.size(); ++i) {
        const Eigen::Isometry3d T = scans[i].T_world_sensor.value_or(Eigen::Isometry3d::Identity());
        mapper.AddScan(i, scans[i].points, T);
    }
    LocalMap map = *mapper.Finish();
    map.id = id;
    return map;
}

OdometryConfig OdometryConfigFor(const std::string& sensor) {
    OdometryConfig config;  // 64-beam: the paper-era defaults (METHOD.md section 1)
    // What the settings from the data choose for a car's smooth turns (README: odometry.turn_hypothesis):
    // no second ICP from the turn-less guess. The handheld Livox walk and 2D lasers keep it.
    config.turn_hypothesis = sensor != "64-beam";
    if (sensor == "livox") {
        config.min_range = 1.0;  // handheld: no ego vehicle to remove
    } else if (sensor == "2d") {
        config.planar = true;
        config.max_range = 30.0;
        config.min_range = 0.2;
    }
    return config;
}

const std::vector<Scan>& FixtureCache::Simulated(const std::string& preset, std::size_t max_scans) {
    const std::string key = "sim:" + preset + ":" + std::to_string(max_scans);
    auto it = scans_.find(key);
    if (it == scans_.end()) it = scans_.emplace(key, SimulatedScans(preset, max_scans)).first;
    return it->second;
}

const std::vector<Scan>& FixtureCache::Dataset(const std::filesystem::path& path, std::size_t max_scans,
                                               double laser_aperture, std::size_t first) {
    const std::string key = "data:" + path.string() + ":" + std::to_string(max_scans) + ":" + std::to_string(first);
    auto it = scans_.find(key);
    if (it == scans_.end()) it = scans_.emplace(key, DatasetScans(path, max_scans, laser_aperture, first)).first;
    return it->second;
}

}  // namespace revisit
