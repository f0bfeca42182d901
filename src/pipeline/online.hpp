#pragma once
/// The online API: feed scans with their poses one at a time; receive each local map as it closes
/// and the closures it makes, refined, verified and applied to the pose graph. `revisit run` is a
/// loop over a reader around this class; a SLAM system embeds it the same way.
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <utility>
#include <vector>

#include "closures/detector.hpp"
#include "closures/local_map.hpp"
#include "closures/map_point_store.hpp"
#include "optimization/closure_consistency.hpp"
#include "optimization/pose_graph.hpp"
#include "config/config.hpp"
#include "pipeline/free_space_gate.hpp"
#include "pipeline/refinement_gate.hpp"
#include "pipeline/scan_trail.hpp"
#include "runfolder/run_state.hpp"

namespace revisit {

/// What one call changed.
struct PipelineUpdate {
    std::optional<MapRecordSummary> closed_map;  ///< the map this scan closed, if any
    std::vector<ClosureRecord> closures;         ///< closures of that map (all methods), verdicts included
};

class ClosurePipeline {
  public:
    /// `store` null: keep map points in memory.
    explicit ClosurePipeline(const PipelineConfig& config, std::unique_ptr<MapPointStore> store = nullptr);

    /// One scan: points in the sensor frame (deskewed if the odometry deskews) and its pose.
    PipelineUpdate AddScan(std::size_t scan_index, const std::vector<Eigen::Vector3f>& points_in_sensor,
                           const Eigen::Isometry3d& T_world_sensor) {
        return AddScan(scan_index, points_in_sensor.data(), points_in_sensor.size(), T_world_sensor);
    }
    /// The same over `count` points the caller owns, read in place during the call (the Python module
    /// passes a numpy array's buffer this way).
    PipelineUpdate AddScan(std::size_t scan_index, const Eigen::Vector3f* points_in_sensor, std::size_t count,
                           const Eigen::Isometry3d& T_world_sensor);
    /// Closes the last map and runs the final batch optimization (after the drift calibration, then the
    /// proximity pass).
    PipelineUpdate Finish();
    /// The heading-drift rate the drift calibration chose at Finish, when it changed it.
    const std::optional<SettingUpdate>& DriftCalibration() const { return drift_calibration_; }
    /// The refinement's RMS gate at the end of the run, when this run's smeared maps raised it (SmearGate).
    std::optional<SettingUpdate> RmsGateUpdate() const;

    /// Map origins after the latest optimization (index = map id).
    const Poses& CorrectedMapPoses() const { return corrected_nodes_; }
    const std::vector<MapRecordSummary>& maps() const { return maps_; }
    /// Every closure record so far. A pair within one session carries no keypoints here (the update that
    /// reported it did): they are its maps' own, detector().maps()[id].keypoints.
    const std::vector<ClosureRecord>& closures() const { return closures_; }
    /// Every skipped, voted-for or compared (query, earlier map) pair of the density detector.
    const std::vector<MapComparison>& comparisons() const { return comparisons_; }
    /// The closure records and comparisons handed over after Finish, leaving them empty here: a
    /// long run holds tens of thousands of records, and a copy alive beside them raised the chain's peak.
    std::vector<ClosureRecord> TakeClosures() { return std::exchange(closures_, {}); }
    std::vector<MapComparison> TakeComparisons() { return std::exchange(comparisons_, {}); }
    const ClosureDetector& detector() const { return detector_; }
    /// Every scan pose re-anchored to its optimized map origin (METHOD.md section 6).
    Poses CorrectTrajectory(const Poses& T_world_sensor, const std::vector<int>& map_of_scan) const;
    /// Accumulated stage timings.
    const std::map<std::string, StageTimer>& timings() const { return timings_; }
    /// Called with every closed map before it is dropped (e.g. to save its density image).
    std::function<void(const LocalMap&, const MapRecord&)> on_map_closed;
    /// Called as the proximity pass at the end registers its map pairs (`done` of `total`): on a long
    /// run that pass takes minutes.
    std::function<void(std::size_t done, std::size_t total)> on_proximity_progress;

  private:
    PipelineUpdate ProcessMap(const LocalMap& map);
    /// `query_planes`: the new map's planes, made on the first closure that needs them and kept for the others.
    ClosureRecord VerifyClosure(const Closure& closure, const std::vector<Eigen::Vector3f>& query_points,
                                std::optional<RefinementQuery>& query_planes);
    /// The new map prepared for registration (RefinementQuery), once per map: its registration onto its
    /// predecessor and each of its closures use the same planes.
    const RefinementQuery* NewMapPlanes(const std::vector<Eigen::Vector3f>& stored, std::optional<RefinementQuery>& planes) const;
    /// Refines `record`'s closure against the stored reference map; a verified one enters the consistency
    /// check (`may_displace`: see ClosureConsistency::Add). `prepared`: the query map already prepared
    /// for registration (the proximity pass registers several references onto one query map).
    void Refine(ClosureRecord& record, const std::vector<Eigen::Vector3f>& query_points, const MapRecord& query_map,
                const RefinementConfig& refinement, bool may_displace, const RefinementQuery* prepared = nullptr);
    /// One round of the proximity pass over the corrected poses (`from_odometry`: over the odometry's, and its
    /// closures may displace the detector's); returns how many registrations were verified.
    std::size_t AddProximityClosures(bool from_odometry = false);
    /// Before the final optimization: with few consistent closures, the odometry's own overlays check them.
    void CheckAgainstOdometryOverlays();
    double FootprintCell() const;  ///< [m] ground cells of the maps' footprints
    /// Whether map `query` returns to where its predecessor went under the pose estimate `T_world_map`:
    /// a scan of each within a tenth of a map's length of the other, a map's length apart in travel.
    bool RevisitsPredecessor(int query, const Poses& T_world_map) const;
    /// Whether the path from map `ref` to map `query` came back under `T_world_map` (proximity.revisit_detour):
    /// the travel between their first scans is at least that many times the straight line, or their scans
    /// meet as RevisitsPredecessor's do. Maps of different sessions always do.
    bool PathReturns(int query, int ref, const Poses& T_world_map) const;
    /// Why verified closure k (of the consistency check) was dropped against the odometry alone.
    std::string OdometryContradiction(const Closure& closure, std::size_t k) const;
    /// Keeps only the maximum pairwise-consistent set of verified closures in the graph (PCM).
    void ApplyConsistency();
    /// After a final optimization: closures the robust kernel weighted below graph_noise.min_weight leave
    /// the graph (reported as rejected by it), and the graph is optimized without them.
    void DropDownweighted();
    /// Lowers the odometry's rotation drift rate (consistency check and graph) to what the consistent
    /// closures show (ClosureConsistencyConfig::calibrate_drift) and checks the closures again.
    void CalibrateDrift();
    void Optimize(bool final);
    void Time(const std::string& stage, double ms);

    PipelineConfig config_;
    std::unique_ptr<MapPointStore> store_;
    LocalMapper mapper_;
    ClosureDetector detector_;
    RefinementGate refinement_gate_;  ///< the RMS gate from consecutive maps' registrations
    FreeSpaceGate free_space_;        ///< 2D lasers: what each map observed, for pairs below the overlap gate
    std::optional<ClosureDetector> elevation_detector_;
    std::vector<MapRecordSummary> maps_;
    std::vector<ClosureRecord> closures_;
    std::vector<MapComparison> comparisons_;
    std::vector<std::vector<Eigen::Vector2d>> footprints_;  ///< per map: its ground cells (MapFootprint)
    std::vector<ScanTrail> trails_;  ///< per map: where its scans were (RevisitsPredecessor, PathReturns)
    Poses nodes_;            ///< odometry map origins
    std::vector<double> node_travel_;  ///< [m] travel at each map origin
    std::vector<Eigen::Vector3d> node_position_integral_;  ///< the consistency check's leg means (AppendPositionIntegral)
    ClosureConsistency consistency_;
    std::vector<PoseGraphEdge> verified_edges_;      ///< one per closure that passed 3D verification
    std::vector<std::size_t> verified_closure_;      ///< closures_ index of each verified edge
    Poses corrected_nodes_;  ///< after the last optimization
    std::vector<PoseGraphEdge> loop_edges_;
    std::vector<std::size_t> loop_edge_closure_;  ///< closures_ index of each loop edge
    std::set<std::size_t> graph_rejected_;        ///< closures_ indices the final graph weighted below min_weight
    std::set<std::size_t> odometry_overlay_;      ///< closures_ indices registered from the odometry's overlay
    int accepted_since_optimization_ = 0;
    std::optional<SettingUpdate> drift_calibration_;
    std::map<std::string, StageTimer> timings_;
};

}  // namespace revisit
