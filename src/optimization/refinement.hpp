#pragma once
/// Fine 3D registration of two local maps from the 2D closure guess, and its verdict.
/// METHOD.md section 5 (refinement, KISS-SLAM style): point-to-plane ICP in Ceres with a
/// robust loss, accepted only when the voxel overlap after alignment is high enough.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "optimization/point_grid.hpp"

namespace revisit {

using Matrix6d = Eigen::Matrix<double, 6, 6>;

struct RefinementConfig {
    // Registration.
    double voxel_size = 0.5;                   ///< [m] both maps are downsampled to this first
    double normal_radius = 1.0;                ///< [m] neighbourhood of the query-map normals (PCA)
    int min_normal_neighbours = 5;             ///< fewer neighbours: no normal, point not used
    double max_surface_variation = 0.1;        ///< lambda_min / sum(lambda) above this: not a plane, point not used
    double initial_max_distance = 2.0;         ///< [m] correspondence gate at the first iteration (covers the 2D guess error)
    /// [m] before ICP, the offset along the query map's up direction within +-this that overlaps the
    /// maps best (steps of voxel_size): a 2D closure measures x, y and yaw only, and its height comes
    /// from the two maps' ground planes, which are metres off on slopes, steps or cluttered ground
    /// (0 = off).
    double vertical_search = 5.0;
    double max_correspondence_distance = 0.9;  ///< [m] gate reached after `gate_decay_iterations` (METHOD.md section 5)
    int gate_decay_iterations = 5;             ///< iterations over which the gate shrinks linearly
    double loss_scale = 0.2;                   ///< [m] Cauchy scale of the point-to-plane residual
    int max_iterations = 30;                   ///< outer ICP iterations (correspondences re-found each time)
    int max_solver_iterations = 3;             ///< Ceres iterations per outer iteration
    int max_solver_points = 4000;              ///< ICP uses an evenly strided subset of this many reference points (speed; the verdict uses all)
    double convergence_translation = 1e-3;     ///< [m] stop when an update moves less than this ...
    double convergence_rotation = 1e-4;        ///< [rad] ... and turns less than this
    // Verdict.
    double overlap_voxel_size = 1.0;           ///< [m] voxels of the overlap coefficient
    double min_overlap = 0.4;                  ///< accept above this overlap [0..1] (KISS-SLAM: 0.4)
    int min_correspondences = 100;             ///< accept with at least this many final correspondences
    double max_rms = 0.25;                     ///< [m] accept below this point-to-plane RMS of the correspondences
    /// The RMS gate is at least this multiple of the median RMS with which each map registers onto its
    /// predecessor (SmearGate: what a true overlap shows under this run's odometry); <= 0: `max_rms` alone.
    double smear_gate_factor = 1.2;
    /// A 2D laser's pair (planar maps with their scans) below `min_overlap`, which counts against the
    /// smaller map's whole extent, is accepted when its walls agree with what the other map observed at
    /// least this share of the time, both ways (optimization/free_space.hpp; 0 = off: `min_overlap` alone).
    double min_free_space_agreement = 0.85;
    double max_correction_translation = 5.0;   ///< [m] a refined pose this far from the guess is a different basin: reject
    double max_correction_rotation = 0.35;     ///< [rad] (20 deg) same, for rotation
    // Uncertainty.
    double min_point_sigma = 0.02;             ///< [m] floor of the per-point noise used for `information`
    /// Neighbouring points' errors are correlated (the same wall, the same ring), so treating
    /// thousands of them as independent makes the information ~100x overconfident. The
    /// information is scaled to this many independent points; <= 0: all correspondences.
    double information_effective_points = 50.0;
};

struct RefinementResult {
    Eigen::Isometry3d T_query_ref = Eigen::Isometry3d::Identity();  ///< maps reference-map points into the query map
    double overlap = 0.0;          ///< voxel overlap coefficient after alignment [0..1]
    double rms = 0.0;              ///< [m] point-to-plane RMS over the final correspondences
    int num_correspondences = 0;   ///< final correspondences within the gate
    int iterations = 0;            ///< outer ICP iterations run
    bool converged = false;        ///< the last update was below the convergence thresholds
    /// Gauss-Newton information of T_query_ref for a right perturbation [translation; rotation],
    /// i.e. T = T_query_ref * ExpSE3(delta), per-point sigma = max(rms, min_point_sigma), scaled
    /// to `information_effective_points`; the pose graph's edge convention. Its shape shows
    /// degenerate directions (corridors). Zero when registration failed.
    Matrix6d information = Matrix6d::Zero();
    bool accepted = false;
    std::string reason;            ///< why not accepted; empty when accepted
};

/// The start of `RefinementResult::reason` when the refined pose moved farther from the guess than
/// `max_correction_*` allow (the proximity pass retries those from a better estimate).
inline constexpr const char* kCorrectionFromGuess = "correction from guess";

/// The query map's share of a registration: downsampled to `voxel_size`, with its planes (normals from
/// `normal_radius` neighbourhoods). The same for every reference registered onto this query map (the
/// proximity pass registers up to `proximity.max_per_map` of them), so it can be prepared once.
class RefinementQuery {
  public:
    struct Plane {
        Eigen::Vector3d point;
        Eigen::Vector3d normal;
    };
    RefinementQuery(const std::vector<Eigen::Vector3d>& query_points_in_query, const RefinementConfig& config,
                    const Eigen::Vector3d& up_in_query = Eigen::Vector3d::UnitZ());

    const std::vector<Eigen::Vector3d>& points() const { return points_; }
    const std::vector<Plane>& planes() const { return planes_; }
    const Eigen::Vector3d& up() const { return up_; }
    /// The planes were taken within the plane orthogonal to `up` (every query point at one height).
    bool planar() const { return planar_; }
    /// The heights along `up` of the lowest and highest point (planar maps: equal).
    double low() const { return low_; }
    double high() const { return high_; }
    /// Whether these planes are the ones `config` asks for.
    bool MadeWith(const RefinementConfig& config) const;
    /// Whether the same points prepared with `up_in_query` would have these planes (they differ only
    /// where the map lies at one height along either vertical: a 2D laser's).
    bool SamePlanesAs(const Eigen::Vector3d& up_in_query) const;

    /// Keeps the grids of the planes built for each gate of the ICP's schedule for the next
    /// registrations onto this query map (the proximity pass registers several references onto one;
    /// a few grids of the planes stay alive while the query does). Registrations onto a query that
    /// keeps its grids must not run concurrently.
    void KeepPlaneGrids() { keep_grids_ = true; }
    /// The grid of the planes' points (in order) with cell edge `gate`: built each call into `built`,
    /// or built once and kept (KeepPlaneGrids).
    const PointGrid& PlaneGrid(double gate, std::optional<PointGrid>& built) const;

  private:
    std::vector<Eigen::Vector3d> points_;
    std::vector<Plane> planes_;
    Eigen::Vector3d up_;
    bool planar_ = false;
    double low_ = 0.0, high_ = 0.0;
    double voxel_size_, normal_radius_, max_surface_variation_;
    int min_normal_neighbours_;
    bool keep_grids_ = false;
    mutable std::vector<std::pair<double, std::unique_ptr<PointGrid>>> grids_;  ///< by gate, when kept
};

/// Registers the reference map onto the query map starting from `T_query_ref_guess`
/// (the 2D closure pose lifted to 3D) and judges the result with the config's thresholds.
/// `up_in_query`: the vertical in the query frame (its ground normal), for the vertical search.
/// Runs the correspondence search in parallel with TBB; Ceres uses as many threads as
/// the caller's tbb::global_control allows.
RefinementResult RefineAlignment(const std::vector<Eigen::Vector3d>& ref_points_in_ref,
                                 const std::vector<Eigen::Vector3d>& query_points_in_query,
                                 const Eigen::Isometry3d& T_query_ref_guess, const RefinementConfig& config,
                                 const Eigen::Vector3d& up_in_query = Eigen::Vector3d::UnitZ());

/// The same with the query map prepared (RefinementQuery), for several references onto one query map.
/// Identical results.
RefinementResult RefineAlignment(const std::vector<Eigen::Vector3d>& ref_points_in_ref, const RefinementQuery& query,
                                 const Eigen::Isometry3d& T_query_ref_guess, const RefinementConfig& config);

/// Ceres thread count that respects the caller's tbb::global_control.
int CeresThreadCount();

}  // namespace revisit
