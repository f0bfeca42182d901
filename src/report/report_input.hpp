#pragma once
/// Everything the HTML report shows, filled by the pipeline from a run folder (issue 8). Plain data, no
/// dependency on the optimization or evaluation modules; heavy data (maps) is fetched on demand by callbacks.
#include "closures/closure.hpp"
#include "closures/density_image.hpp"
#include "closures/local_map.hpp"

#include <Eigen/Geometry>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace revisit {

/// Poses with timestamps; index i is scan i of the sequence (closures refer to scans by index).
struct TimedTrajectory {
    std::vector<double> timestamps;                  ///< [s]
    std::vector<Eigen::Isometry3d> T_world_sensor;
    bool Empty() const { return T_world_sensor.empty(); }
};

struct StageTiming {
    std::string stage;
    double seconds = 0.0;  ///< [s]
};

/// One detected closure and what became of it.
struct ClosureEntry {
    Closure closure;
    /// Registered by the proximity pass (the corrected poses laid the two maps over each other), not detected:
    /// no image matches, no votes; its evidence is the registration's overlap and RMS.
    bool proximity = false;
    bool accepted = false;                   ///< in the final pose graph
    bool reached_threshold = false;          ///< reached the acceptance threshold (detector.min_inliers): verified in 3D
    bool verified = false;                   ///< passed 3D verification (may still be rejected by the pose graph)
    std::string reason;                      ///< why rejected, or the graph weight when accepted (no status word)
    std::optional<double> fitness;           ///< refinement fitness (e.g. inlier ratio of the ICP) [0..1]
    std::optional<double> rmse;              ///< refinement residual [m]
    std::optional<Eigen::Matrix4d> T_query_ref_refined;  ///< after refinement, when refined
    std::optional<double> gt_translation_error;  ///< [m] planar, against ground truth, when known
    std::optional<double> gt_rotation_error;     ///< [deg] yaw
    std::optional<bool> gt_true_positive;        ///< ground truth says the two maps overlap
    bool judged_false = false;                   ///< accepted, and the evaluation calls it false against the reference
};

struct PrCurvePoint {
    double threshold = 0.0;
    double precision = 0.0;  ///< [0..1]
    double recall = 0.0;     ///< [0..1]
    double F1() const { return precision + recall > 0.0 ? 2.0 * precision * recall / (precision + recall) : 0.0; }
};

/// One evaluated method's precision-recall sweep; the max-F1 point is found by MaxF1 when not given.
struct PrCurve {
    std::string method;
    std::vector<PrCurvePoint> points;
    std::optional<PrCurvePoint> max_f1;
};
PrCurvePoint MaxF1(const PrCurve& curve);

/// Absolute pose error over time [m].
struct ErrorSeries {
    std::vector<double> timestamps;  ///< [s]
    std::vector<double> values;      ///< [m]
};

struct TextTable {
    std::vector<std::string> header;
    std::vector<std::vector<std::string>> rows;
};

/// "Were my revisits found?", from the evaluation (already formatted).
struct RevisitFindings {
    std::vector<std::string> lines;  ///< true / false counts, revisit coverage
    TextTable funnel;                ///< overlapping map pairs reaching each stage, detector and proximity pass
    TextTable per_stage;             ///< missed map pairs per stage
    TextTable missed;                ///< one row per missed map pair
};

/// How a user renders a page on demand: the report lists "<kInspectCommand> --closure N" for candidates
/// without a page and "--map N" for maps without one (ReportInput::run_dir says which folder).
inline constexpr const char* kInspectCommand = "revisit inspect RUN_DIR";

struct ReportInput {
    std::string title = "revisit report";
    std::vector<std::string> dataset_summary;  ///< one line each (path, format, scans, duration, length...)
    std::string config_text;                   ///< the run's configuration, shown verbatim
    std::vector<std::pair<std::string, std::string>> counts;  ///< e.g. {"local maps", "46"}
    std::vector<StageTiming> timings;

    TimedTrajectory odometry;
    TimedTrajectory corrected;
    TimedTrajectory reference;  ///< ground truth, empty when unknown
    std::vector<std::size_t> odometry_fallbacks;  ///< scans whose odometry pose is only a prediction
    std::vector<std::string> setting_updates;     ///< settings that followed the data mid-run, one line each

    std::vector<ClosureEntry> closures;  ///< the detector's candidates and the proximity pass's accepted closures
    std::size_t proximity_registered = 0;  ///< map pairs the proximity pass registered (accepted or not)
    /// The trajectory is the input poses (`--poses dataset`), and the reference is those same poses: APE
    /// "before" is zero by construction.
    bool reference_is_input = false;
    std::vector<int> map_ids;  ///< the run's local maps
    std::vector<ScanRange> map_scans;  ///< scan range of each map in map_ids (same order), or empty when unknown
    /// Closures the evaluation counts as true / false against the reference (metrics.json), when evaluated.
    std::optional<int> true_closures;
    std::optional<int> false_closures;
    /// The run folder that kInspectCommand's RUN_DIR stands for, named once on the index: the pages
    /// themselves do not name it, so a run folder's pages are the same wherever it was written or moved.
    std::string run_dir;
    std::vector<PrCurve> pr_curves;
    ErrorSeries ape_before;  ///< odometry against reference
    ErrorSeries ape_after;   ///< corrected against reference
    TextTable metrics;       ///< from the evaluation, already formatted
    /// With a reference for some scans only: what the figures cover ("... 180 of 292 scans ..."); empty
    /// when they cover the whole run.
    std::string evaluation_scope;
    std::optional<RevisitFindings> revisits;  ///< with reference poses only

    /// On-demand data (each may be empty: the pictures that need it are then left out).
    std::function<std::optional<LocalMap>(int map_id)> load_local_map;
    std::function<std::optional<DensityImage>(int map_id)> load_density_image;  ///< computed from the map if absent
    /// ORB keypoints of a map's density image [pixels] (MapRecord::keypoints), drawn on `inspect --maps` pages.
    std::function<std::vector<Eigen::Vector2f>(int map_id)> load_keypoints;
    /// Corrected global map [m, world frame], already decimated to what a picture needs (~1-2 M points).
    std::function<std::vector<Eigen::Vector3f>()> load_global_map;
};

}  // namespace revisit
