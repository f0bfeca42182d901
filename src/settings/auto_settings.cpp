#include "settings/auto_settings.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

#include "core/error.hpp"
#include "io/reader.hpp"
#include "odometry/odometry_config.hpp"
#include "settings/motion_profile.hpp"

namespace revisit {
namespace {

/// Scans profiled for the settings (the first seconds of a sequence).
constexpr std::size_t kProfileScans = 10;
/// 2D lasers: scans read at most while looking for scan pairs to measure the aperture.
constexpr std::size_t kMaxApertureScans = 5000;
/// An explicit value this far (either way) from the data's suggestion gets a warning.
constexpr double kContradictionFactor = 3.0;

/// Points a scan must keep after the odometry's source downsampling for a well-conditioned ICP:
/// a 3D scan constrains six degrees of freedom from a few surfaces, a 2D scan three from walls.
constexpr double kMinSourcePoints3D = 1000.0;
constexpr double kMinSourcePoints2D = 150.0;
/// A 2D laser's ICP needs correspondences for at least this share of the points a scan registers
/// (odometry.min_correspondences; the default 20 is a few percent of a 3D scan's points).
constexpr double kMinCorrespondenceShare2D = 0.2;
/// ... and never fewer than this many: twice the three unknowns of a planar pose.
constexpr double kMinCorrespondences2D = 6.0;
/// [deg] rings at least this far apart in elevation get point-to-plane registration (VLP-16: 2 deg).
constexpr double kSparseRingSpacingDeg = 1.0;
/// [deg] a constant-velocity turn prediction off by more than this (90th percentile over the motion
/// probe's steps) calls for the turn hypothesis. Measured: cars 0.13-0.20 deg (the demo, city-16,
/// city-livox, KITTI 00), handheld walks 1.8 deg (the simulated campus walks) to 10.3 deg (the real
/// Livox walk): a factor of 2.5 to 3.6 either side.
constexpr double kSwayTurnDeg = 0.5;

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
bool IsFlag(const std::string& key) {
    return key == "odometry.planar" || key == "odometry.deskew" || key == "ground.enabled" || key == "features.pad_border" ||
           key == "evaluation.planar" || key == "local_map.carry_over" || key == "odometry.turn_hypothesis" ||
           key == "odometry.ring_start" || key == "detector.rematch";
}

/// The value as the schema reads it: a name, true/false, or the number.
std::string ValueText(const SettingChoice& c) {
    if (!c.text.empty()) return c.text;
    if (IsFlag(c.key)) return c.value != 0.0 ? "true" : "false";
    std::ostringstream value;
    value << std::setprecision(10) << c.value;
    return value.str();
}

double RoundTo(double value, double step) { return std::round(value / step) * step; }

/// The median points a scan keeps for registration at the voxel `voxel` (0: not profiled).
double RegisteredPointsAt(const DataProfile& p, double voxel) {
    for (std::size_t k = 0; k < p.voxel_candidates.size() && k < p.source_points.size(); ++k)
        if (std::abs(p.voxel_candidates[k] - voxel) < 1e-9) return p.source_points[k];
    return 0.0;
}

/// The map voxel: a tenth of the median range (KISS-ICP's max_range / 100 on a 10 m-median street
/// scene: 1 m), but no coarser than what leaves a scan enough points to register.
SettingChoice ChooseVoxel(const DataProfile& p) {
    const double by_scale = std::clamp(p.range_p50 / 10.0, VoxelCandidates().front(), VoxelCandidates().back());
    const double min_points = p.planar ? kMinSourcePoints2D : kMinSourcePoints3D;
    double voxel = VoxelCandidates().front();
    double points = p.source_points.empty() ? 0.0 : p.source_points.front();
    // A scan that keeps fewer than the minimum even at the finest voxel (a 2D laser of ~180 beams) is
    // sparse at every voxel: the floor cannot be met, and binding it would register at a voxel far
    // below the scene's scale (intel: 0.05 m for a 1.4 m median range; 8 of 16 verified closures
    // accepted, walls doubled). Such a scan loses points with every coarser voxel, so the scale rule
    // is not rounded up: the largest candidate at most a tenth of the median range.
    const bool sparse_at_any_voxel = points < min_points;
    const double tolerance = sparse_at_any_voxel ? 1.0 : 1.1;
    bool limited = false;
    for (std::size_t k = 0; k < p.voxel_candidates.size(); ++k) {
        if (p.voxel_candidates[k] > tolerance * by_scale) break;  // 0.98 m of a 9.8 m median is 1 m
        if (k > 0 && !sparse_at_any_voxel && p.source_points[k] < min_points) {
            limited = true;
            break;
        }
        voxel = p.voxel_candidates[k];
        points = p.source_points[k];
    }
    std::string reason = "median range " + Number(p.range_p50) + " m / 10";
    if (limited) reason += ", limited to keep >= " + Number(min_points, 0) + " points per scan after downsampling";
    if (sparse_at_any_voxel) reason += " (fewer than " + Number(min_points, 0) + " points per scan at any voxel)";
    reason += " (" + Number(points, 0) + " points registered per scan)";
    return {"odometry.voxel_size", voxel, {}, reason};
}

/// A local map spans about this much time of motion: the paper's 100 m maps at KITTI's ~10 m/s,
/// about 10 m of a walk (METHOD.md section 2; README "Settings from the data").
constexpr double kMapSeconds = 10.0;
/// Local maps at least this long [m]: shorter ones hold too little structure for a density image.
constexpr double kMinMapLength = 5.0;
/// A 2D laser's map gathers walls over about twice the range most of its beams reach.
constexpr double kPlanarMapRanges = 2.0;
/// Below this map length [m] (or a field of view below kWideFovDeg) the detector's small-scale
/// settings apply (METHOD.md 5b): fewer matches needed, robust image scaling, a keypoint budget.
constexpr double kDrivingMapLength = 50.0;
constexpr double kWideFovDeg = 180.0;
/// A ground tilted more than this in the sensor frame [deg]: maps are levelled before projecting.
constexpr double kLevelTiltDeg = 5.0;

/// What the closure detector needs from the data: the local maps' length and voxels, the density
/// image's pixels, levelling, the skip of recent maps and the match thresholds (issue 16, one place
/// with the odometry's choices). `v` is the odometry's map voxel.
void ChooseClosureSettings(const DataProfile& p, double v, double max_range, std::optional<double> given_length,
                           std::vector<SettingChoice>& choices) {
    double length = 100.0;  // the paper's tau_m
    std::string why = "the paper's 100 m (speed unknown)";
    if (p.planar) {
        length = std::clamp(RoundTo(kPlanarMapRanges * p.range_p95, kMinMapLength), kMinMapLength, 100.0);
        why = Number(kPlanarMapRanges, 0) + " x the 95% range " + Number(p.range_p95, 1) + " m (a 2D laser's walls)";
    } else if (p.motion.known()) {
        length = std::clamp(RoundTo(kMapSeconds * p.motion.speed, 0.5), kMinMapLength, 100.0);
        why = Number(kMapSeconds, 0) + " s at " + Number(p.motion.speed) + " m/s" + (length >= 100.0 ? ", at most the paper's 100 m" : "");
    }
    choices.push_back({"local_map.split_distance", length, {}, why});
    if (given_length) length = *given_length;  // what scales with the map length follows the user's
    const bool small = p.planar || length < kDrivingMapLength || p.horizontal_fov_deg < kWideFovDeg;
    // Recent maps share the current map's scans: skip by travel (twice a map) rather than by count,
    // which fails when maps are short or the sequence is (METHOD.md 5b).
    if (small) {
        choices.push_back({"detector.skip_recent_maps", 0.0, {}, "skip recent maps by travel instead"});
        choices.push_back({"detector.skip_recent_travel", RoundTo(2.0 * length, 0.5), {}, "two local maps of travel"});
        // The ground truth at the data's scale: the paper's 100 m pair range and 200 m of travel
        // between the two segments are a car's, and leave no pair on a 60 m walk or a floor of a
        // building. Pairs within the sensor's range, as far apart along the path as the detector's
        // own skip: the ground truth holds what the detector is allowed to find.
        choices.push_back({"evaluation.max_range", max_range, {}, "the odometry's range"});
        choices.push_back({"evaluation.min_travel", RoundTo(2.0 * length, 0.5), {}, "the detector's skip of recent maps (paper: 2 x max_range for a car)"});
    }
    if (!p.planar && length < kDrivingMapLength) {
        // A walk returns to its start at the end of the recording, into a last map that may hold only
        // a few metres: seeded with the points of its predecessor within a map's length, every map
        // shows enough of its place to be matched (later code's carry-over; scans stay in one map).
        choices.push_back({"local_map.carry_over", 1.0, {}, "short maps: each starts with its predecessor's nearby points"});
        choices.push_back({"local_map.carry_radius", length, {}, "one map length"});
    }
    const double map_voxel = p.planar ? v : std::min(v, 1.0);
    choices.push_back({"local_map.voxel_size", map_voxel, {}, "the odometry's map voxel"});
    const double pixel = p.planar ? v : RoundTo(0.5 * map_voxel, 0.01);
    choices.push_back({"density.resolution", pixel, {}, p.planar ? "one map voxel per pixel" : "half a map voxel per pixel (paper: 1 m voxels, 0.5 m pixels)"});
    const bool tilted = p.ground_tilt_deg > kLevelTiltDeg;
    const bool level = !p.planar && (tilted || length < kDrivingMapLength);
    choices.push_back({"ground.enabled", level ? 1.0 : 0.0, {},
                       p.planar ? "a 2D laser's maps are flat"
                       : tilted ? "the ground is tilted " + Number(p.ground_tilt_deg, 1) + " deg in the sensor frame"
                       : level  ? "maps shorter than " + Number(kDrivingMapLength, 0) + " m (a carried sensor sways)"
                                : "the sensor is level (ground tilt " + Number(std::max(0.0, p.ground_tilt_deg), 1) + " deg)"});
    if (small) {
        const std::string reason = p.planar                      ? "a 2D laser"
                                   : length < kDrivingMapLength ? "maps shorter than " + Number(kDrivingMapLength, 0) + " m"
                                                                : "a narrow field of view";
        choices.push_back({"detector.selection", 0.0, "all_above_min", reason + ": every map with enough matches"});
        choices.push_back({"detector.min_matches", 10.0, {}, reason + " (paper: 10 for small fields of view)"});
        // Small maps hold fewer keypoints: true candidates of walks show 6-9 inliers, false ones 3-5;
        // the 3D refinement and the consistency check verify what passes (later code: 6).
        choices.push_back({"detector.min_inliers", 6.0, {}, reason + ": fewer keypoints per map (later code: 6)"});
        // That gate was measured on the tree's matches: verifying on every mutual match raises the false
        // candidates' inliers too (3 false closures on the simulated indoor floor at 6 inliers).
        choices.push_back({"detector.rematch", 0.0, {}, reason + ": the 6-inlier gate counts the tree's matches"});
        choices.push_back({"density.scaling", 0.0, "percentile", reason + ": robust image scaling"});
        choices.push_back({"features.min_keypoints", 150.0, {}, reason + ": adaptive keypoint budget"});
        choices.push_back({"features.pad_border", 1.0, {}, reason + ": keypoints near the image border"});
    }
    if (p.planar) {
        // The 3D refinement works at the 2D maps' scale: the indoor proportions of the paper's
        // driving settings (0.5 m voxels, 1 m normals, 2 -> 0.9 m gates, 0.25 m RMS).
        choices.push_back({"refinement.voxel_size", 2.0 * v, {}, "two map voxels"});
        choices.push_back({"refinement.normal_radius", 6.0 * v, {}, "six map voxels"});
        choices.push_back({"refinement.initial_max_distance", 20.0 * v, {}, "twenty map voxels"});
        choices.push_back({"refinement.max_correspondence_distance", 6.0 * v, {}, "six map voxels"});
        choices.push_back({"refinement.max_rms", 2.0 * v, {}, "two map voxels"});
        choices.push_back({"refinement.min_correspondences", 50.0, {}, "a 2D map has fewer points"});
        // The ICP's floor of 20 correspondences is 40% of a sparse laser's ~50 registered points: a key
        // frame whose front looks into a room the map has not seen then keeps the constant-velocity
        // prediction, and the walk is lost from there (seattle with half its beams, docs/method.md).
        // With wheel odometry such a frame keeps the wheels' motion, which is right: the floor stays.
        const double registered = RegisteredPointsAt(p, v);
        const double floor = std::max(std::round(kMinCorrespondenceShare2D * registered), kMinCorrespondences2D);
        if (!p.has_odometry_prior && registered > 0.0 && floor < OdometryConfig{}.min_correspondences)
            choices.push_back({"odometry.min_correspondences", floor, {},
                               "a fifth of the " + Number(registered, 0) + " points registered per scan"});
        // A revisit in a building often crosses or runs along a corridor of the other map and shares
        // 0.15-0.3 of it; such pairs are verified by what both maps observed (free_space.hpp).
        choices.push_back({"proximity.min_overlap", 0.15, {}, "a 2D laser: crossing corridors, verified by their free space"});
        choices.push_back({"output.map_voxel", v, {}, "the map voxel"});
        choices.push_back({"output.global_map_voxel", v, {}, "the map voxel"});
        // Indoor planar odometry drifts mostly in heading (the indoor2d preset's measurement: at the
        // driving 3e-4 rad/m the graph rejects 11 of intel's 17 verified closures, at 2e-3 none).
        choices.push_back({"graph.odometry_rotation_per_m", 0.002, {}, "a 2D laser's odometry drifts in heading"});
        choices.push_back({"evaluation.planar", 1.0, {}, "a 2D laser"});
        choices.push_back({"scan_context.max_radius", max_range, {}, "the odometry's range"});
        choices.push_back({"scan_context.sensor_height", 0.0, {}, "a 2D laser"});
    }
}

}  // namespace

double MaxRangeFor(double range_p99) { return std::clamp(std::ceil(1.5 * range_p99 / 10.0) * 10.0, 30.0, 300.0); }

std::vector<SettingChoice> ChooseSettings(const DataProfile& p, const std::optional<ApertureEstimate>& aperture,
                                          std::optional<double> given_map_length) {
    std::vector<SettingChoice> choices;
    if (p.empty()) return choices;
    if (aperture && aperture->contradicts) {
        choices.push_back({"input.laser_aperture_deg", aperture->measured_deg, {},
                           "the file states " + Number(aperture->stated_deg, 1) + " deg; " + std::to_string(aperture->pairs) +
                               " scan pairs agree best at " + Number(aperture->measured_deg, 1) + " deg"});
    }
    const SettingChoice voxel = ChooseVoxel(p);
    const double v = voxel.value;
    choices.push_back({"odometry.planar", p.planar ? 1.0 : 0.0, {},
                       p.planar ? "every point lies at z = 0 (a 2D laser): x, y, yaw only" : "3D points"});
    // The map radius: everything the sensor sees except stray far returns.
    const double max_range = MaxRangeFor(p.range_p99);
    choices.push_back({"odometry.max_range", max_range, {},
                       "99% of the points lie within " + Number(p.range_p99, 1) + " m (x 1.5)"});
    choices.push_back({"odometry.min_range", std::min(RoundTo(0.5 * p.range_p01, 0.05), 3.0), {},
                       "half the 1st-percentile range " + Number(p.range_p01) + " m: drops the platform, keeps the near scene"});
    choices.push_back(voxel);
    choices.push_back({"odometry.initial_threshold", RoundTo(2.0 * v, 0.01), {},
                       "2 map voxels (KISS-ICP: 2 m for 1 m voxels)"});
    choices.push_back({"odometry.min_motion_th", RoundTo(0.1 * v, 0.001), {},
                       "a tenth of a map voxel (KISS-ICP: 0.1 m for 1 m voxels)"});
    choices.push_back({"odometry.deskew", p.has_point_times ? 1.0 : 0.0, {},
                       p.has_point_times ? "the scans carry per-point times" : "no per-point times"});
    // The turn hypothesis (a second ICP from the translation-only guess whenever the predicted turn moves
    // points by more than a voxel) is for a swaying sensor whose turns reverse between scans; a car's
    // smooth turns are predicted well, and on the demo it cost 60% of the odometry's time for no gain
    // (odometry APE 1.98 m with it, 1.59 m without). Measured only on the lidar odometry's own steps:
    // a wheel-odometry prior measures the turn, and the hypothesis never runs with one.
    if (p.motion.known() && p.motion.source == "lidar odometry" && !p.planar) {
        const double deg = p.motion.turn_misprediction * 180.0 / M_PI;
        const bool sway = deg > kSwayTurnDeg;
        choices.push_back({"odometry.turn_hypothesis", sway ? 1.0 : 0.0, {},
                           "the constant-velocity turn is off by " + Number(deg) + " deg (90th percentile): " +
                               (sway ? "a swaying sensor" : "smooth turns")});
    }
    // Rings a degree or more apart leave walls sampled in sparse lines whose point-to-point pull is a
    // pitch (src/sim/README.md, "Sparse and narrow sensors"); finer rings (HDL-64: 0.4 deg) and
    // non-repetitive patterns keep KISS-ICP's point-to-point (point-to-plane loses the Livox walk).
    const bool sparse_rings = p.ring_spacing_deg >= kSparseRingSpacingDeg;
    choices.push_back({"odometry.residual", sparse_rings ? 1.0 : 0.0, sparse_rings ? "point_to_plane" : "point_to_point",
                       p.rings > 1 ? std::to_string(p.rings) + " rings " + Number(p.ring_spacing_deg) + " deg apart" +
                                         (sparse_rings ? ": sparse on walls" : "")
                                   : std::string(p.planar ? "a 2D laser" : "no distinct rings")});
    if (!p.planar) {
        choices.push_back({"odometry.ring_start", p.rings > 1 ? 1.0 : 0.0, {},
                           p.rings > 1 ? "ground rings: point-to-plane until the motion is measured"
                                       : "no distinct rings: nothing snaps at the start"});
    }
    ChooseClosureSettings(p, v, max_range, given_map_length, choices);
    return choices;
}

AutoSettings ApplyAutoSettings(PipelineConfig& config, const DataProfile& profile, const std::optional<ApertureEstimate>& aperture) {
    AutoSettings result;
    result.profile = profile;
    result.aperture = aperture;
    if (aperture && aperture->contradicts) result.profile.horizontal_fov_deg = aperture->measured_deg;
    auto schema = MakeConfigSchema(config);
    std::optional<double> given_map_length;
    if (config.explicit_keys.count("local_map.split_distance") != 0) given_map_length = schema.Number("local_map.split_distance");
    result.choices = ChooseSettings(profile, aperture, given_map_length);
    if (profile.far_range > 0.0) {
        result.warnings.push_back("scan " + std::to_string(profile.far_scan) + " has a point " + Number(profile.far_range, 0) +
                                  " m away (no sensor measures beyond " + Number(kMaxPlausibleRange, 0) +
                                  " m): damaged points or another unit?");
    }
    for (auto& choice : result.choices) {
        if (config.explicit_keys.count(choice.key) == 0) {
            schema.ApplyOverride(choice.key + "=" + ValueText(choice));
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
    if (aperture && aperture->doubtful && config.explicit_keys.count("input.laser_aperture_deg") == 0) {
        result.warnings.push_back("2D laser aperture kept at " + Number(aperture->used_deg, 1) + " deg, though " + aperture->Describe() +
                                  ": not beyond doubt; --set input.laser_aperture_deg=... to choose");
    }
    return result;
}

AutoSettings ConfigureFromData(PipelineConfig& config, const std::filesystem::path& dataset) {
    if (!config.input.auto_settings) return {};
    auto reader = OpenDataset(dataset, MakeReaderOptions(config.input));
    DataProfiler profiler(kProfileScans);
    ApertureChecker checker;
    std::vector<Scan> profiled;  // the first scans, registered again once the odometry's settings are known
    std::optional<MotionMeter> motion;
    DataProfile profile;
    // The odometry's settings follow from the profile; with them, the speed (the local maps' length)
    // from the same first scans and those that follow.
    const auto start_motion = [&] {
        profile = profiler.Profile();
        PipelineConfig odometry_config = config;
        ApplyAutoSettings(odometry_config, profile, checker.Estimate());
        motion.emplace(odometry_config.odometry);
        for (const auto& s : profiled) motion->Add(s);
        profiled.clear();
    };
    std::size_t read = 0;
    bool planar_beams = false;
    try {
        while (auto scan = reader->Next()) {
            ++read;
            planar_beams = planar_beams || scan->planar_beams.has_value();
            checker.Add(*scan);
            if (!profiler.Done()) {
                profiler.Add(*scan);
                profiled.push_back(std::move(*scan));
                if (!profiler.Done()) continue;
                start_motion();
            } else if (!motion->Done()) {
                motion->Add(*scan);
            }
            const bool aperture_done = !planar_beams || checker.Done() || read >= kMaxApertureScans;
            if (motion && motion->Done() && aperture_done) break;
        }
    } catch (const DatasetError&) {
        // Damaged input after some scans: profile what was read; the run itself reports the damage
        // (or keeps the scans with --allow-truncated).
        if (read == 0) throw;
    }
    if (!motion) start_motion();  // fewer scans than the profile wanted
    profile.motion = motion->Profile();
    return ApplyAutoSettings(config, profile, checker.Estimate());
}

std::vector<std::string> AutoSettings::Describe() const {
    std::vector<std::string> lines;
    for (const auto& c : choices) {
        const std::string value = !c.text.empty() || IsFlag(c.key) ? ValueText(c) : Number(c.value, 3);
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
