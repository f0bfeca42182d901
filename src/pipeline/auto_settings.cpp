#include "pipeline/auto_settings.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

#include "core/error.hpp"
#include "io/reader.hpp"

namespace revisit {
namespace {

/// Scans profiled for the settings (the first seconds of a sequence).
constexpr std::size_t kProfileScans = 10;
/// 2D lasers: scans read at most while looking for turns to measure the aperture.
constexpr std::size_t kMaxApertureScans = 5000;
/// An explicit value this far (either way) from the data's suggestion gets a warning.
constexpr double kContradictionFactor = 3.0;

/// Points a scan must keep after the odometry's source downsampling for a well-conditioned ICP:
/// a 3D scan constrains six degrees of freedom from a few surfaces, a 2D scan three from walls.
constexpr double kMinSourcePoints3D = 1000.0;
constexpr double kMinSourcePoints2D = 150.0;

std::string Number(double value, int digits = 2) {
    std::ostringstream out;
    out << std::fixed << std::setprecision(digits) << value;
    std::string s = out.str();
    if (s.find('.') != std::string::npos) {  // no trailing zeros: "0.4", "90"
        s.erase(s.find_last_not_of('0') + 1);
        if (s.back() == '.') s.pop_back();
    }
    return s;
}

/// Choices stored as 0/1 that the schema takes as true/false.
bool IsFlag(const std::string& key) { return key == "odometry.planar" || key == "odometry.deskew"; }

double RoundTo(double value, double step) { return std::round(value / step) * step; }

/// The map voxel: a tenth of the median range (KISS-ICP's max_range / 100 on a 10 m-median street
/// scene: 1 m), but no coarser than what leaves a scan enough points to register.
SettingChoice ChooseVoxel(const DataProfile& p) {
    const double by_scale = std::clamp(p.range_p50 / 10.0, VoxelCandidates().front(), VoxelCandidates().back());
    const double min_points = p.planar ? kMinSourcePoints2D : kMinSourcePoints3D;
    double voxel = VoxelCandidates().front();
    double points = p.source_points.empty() ? 0.0 : p.source_points.front();
    bool limited = false;
    for (std::size_t k = 0; k < p.voxel_candidates.size(); ++k) {
        if (p.voxel_candidates[k] > 1.1 * by_scale) break;  // 0.98 m of a 9.8 m median is 1 m
        if (k > 0 && p.source_points[k] < min_points) {
            limited = true;
            break;
        }
        voxel = p.voxel_candidates[k];
        points = p.source_points[k];
    }
    std::string reason = "median range " + Number(p.range_p50) + " m / 10";
    if (limited) reason += ", limited to keep >= " + Number(min_points, 0) + " points per scan after downsampling";
    reason += " (" + Number(points, 0) + " points registered per scan)";
    return {"odometry.voxel_size", voxel, reason};
}

}  // namespace

std::vector<SettingChoice> ChooseSettings(const DataProfile& p, const std::optional<ApertureEstimate>& aperture) {
    std::vector<SettingChoice> choices;
    if (p.empty()) return choices;
    if (aperture && aperture->contradicts) {
        choices.push_back({"input.laser_aperture_deg", aperture->measured_deg,
                           "the file states " + Number(aperture->stated_deg, 1) + " deg; " + std::to_string(aperture->pairs) +
                               " turns measured against the wheel odometry say " + Number(aperture->measured_deg, 1) + " deg"});
    }
    const SettingChoice voxel = ChooseVoxel(p);
    const double v = voxel.value;
    choices.push_back({"odometry.planar", p.planar ? 1.0 : 0.0,
                       p.planar ? "every point lies at z = 0 (a 2D laser): x, y, yaw only" : "3D points"});
    // The map radius: everything the sensor sees except stray far returns.
    const double max_range = std::clamp(std::ceil(1.5 * p.range_p99 / 10.0) * 10.0, 30.0, 300.0);
    choices.push_back({"odometry.max_range", max_range,
                       "99% of the points lie within " + Number(p.range_p99, 1) + " m (x 1.5)"});
    choices.push_back({"odometry.min_range", std::min(RoundTo(0.5 * p.range_p01, 0.05), 3.0),
                       "half the 1st-percentile range " + Number(p.range_p01) + " m: drops the platform, keeps the near scene"});
    choices.push_back(voxel);
    choices.push_back({"odometry.initial_threshold", RoundTo(2.0 * v, 0.01),
                       "2 map voxels (KISS-ICP: 2 m for 1 m voxels)"});
    choices.push_back({"odometry.min_motion_th", RoundTo(0.1 * v, 0.001),
                       "a tenth of a map voxel (KISS-ICP: 0.1 m for 1 m voxels)"});
    choices.push_back({"odometry.deskew", p.has_point_times ? 1.0 : 0.0,
                       p.has_point_times ? "the scans carry per-point times" : "no per-point times"});
    return choices;
}

AutoSettings ApplyAutoSettings(PipelineConfig& config, const DataProfile& profile, const std::optional<ApertureEstimate>& aperture) {
    AutoSettings result;
    result.profile = profile;
    result.aperture = aperture;
    if (aperture && aperture->contradicts) result.profile.horizontal_fov_deg = aperture->measured_deg;
    result.choices = ChooseSettings(profile, aperture);
    auto schema = MakeConfigSchema(config);
    for (auto& choice : result.choices) {
        if (config.explicit_keys.count(choice.key) == 0) {
            std::ostringstream value;
            value << std::setprecision(10) << choice.value;
            schema.ApplyOverride(choice.key + "=" + (IsFlag(choice.key) ? (choice.value != 0.0 ? "true" : "false") : value.str()));
            choice.applied = true;
            continue;
        }
        // Warn only about the scale of the scene and the sensor's kind: a preset's finer thresholds
        // or a shorter minimum range are choices, not contradictions.
        if (choice.key != "odometry.max_range" && choice.key != "odometry.voxel_size" && choice.key != "odometry.planar") continue;
        const double given = schema.Number(choice.key).value_or(choice.value);
        const bool far = given <= 0.0 || choice.value <= 0.0
                             ? (given == 0.0) != (choice.value == 0.0)
                             : std::max(given / choice.value, choice.value / given) > kContradictionFactor;
        if (far) {
            result.warnings.push_back(choice.key + " = " + Number(given, 3) + " was given, but the data suggests " +
                                      Number(choice.value, 3) + ": " + choice.reason);
        }
    }
    if (aperture && aperture->contradicts && config.explicit_keys.count("input.laser_aperture_deg") == 0) {
        result.warnings.push_back("2D laser aperture corrected from " + Number(aperture->used_deg, 1) + " to " +
                                  Number(aperture->measured_deg, 1) + " deg (" + aperture->Describe() +
                                  "); --set input.laser_aperture_deg=... to choose");
    }
    return result;
}

AutoSettings ConfigureFromData(PipelineConfig& config, const std::filesystem::path& dataset) {
    if (!config.input.auto_settings) return {};
    auto reader = OpenDataset(dataset, MakeReaderOptions(config.input));
    DataProfiler profiler(kProfileScans);
    ApertureChecker checker;
    std::size_t read = 0;
    bool planar_beams = false;
    try {
        while (auto scan = reader->Next()) {
            ++read;
            planar_beams = planar_beams || scan->planar_beams.has_value();
            profiler.Add(*scan);
            checker.Add(*scan);
            const bool aperture_done = !planar_beams || checker.Done() || read >= kMaxApertureScans;
            if (profiler.Done() && aperture_done) break;
        }
    } catch (const DatasetError&) {
        // Damaged input after some scans: profile what was read; the run itself reports the damage
        // (or keeps the scans with --allow-truncated).
        if (read == 0) throw;
    }
    return ApplyAutoSettings(config, profiler.Profile(), checker.Estimate());
}

std::vector<std::string> AutoSettings::Describe() const {
    std::vector<std::string> lines;
    for (const auto& c : choices) {
        const std::string value = IsFlag(c.key) ? (c.value != 0.0 ? "true" : "false") : Number(c.value, 3);
        lines.push_back(c.key + " = " + value + (c.applied ? "" : " (not applied: given explicitly)") + "  <- " + c.reason);
    }
    return lines;
}

void PrintAutoSettings(std::ostream& log, const AutoSettings& settings, const std::filesystem::path& dataset) {
    if (settings.profile.empty()) return;
    log << "revisit: settings from the data of " << dataset.string() << ":\n";
    for (const auto& line : settings.profile.Describe()) log << "  " << line << '\n';
    if (settings.aperture) log << "  2D laser: " << settings.aperture->Describe() << '\n';
    for (const auto& line : settings.Describe()) log << "  " << line << '\n';
    for (const auto& w : settings.warnings) log << "warning: " << dataset.string() << ": " << w << '\n';
}

}  // namespace revisit
