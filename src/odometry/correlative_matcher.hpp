#pragma once
/// Correlative 2D scan matching (after Olson, "Real-time correlative scan matching", ICRA 2009): an
/// exhaustive search over a window of (x, y, yaw) for the pose under which a scan's points fall on
/// the most likely cells of a grid rasterized from reference points. Multi-resolution: a cell of level
/// l holds the maximum of the finest grid over the 2^l x 2^l cells from it, so a level-l score bounds
/// every finer translation it covers, and branch and bound visits only the few blocks that can still
/// win. It needs no initial guess inside ICP's basin: it starts the ICP when the motion is unknown
/// (no wheel odometry) or the ICP from the prediction failed.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstddef>
#include <vector>

namespace revisit {

struct CorrelativeMatchConfig {
    double resolution = 0.05;      ///< [m] finest grid cell (coarser when the scan's extent needs it)
    double linear_window = 1.5;    ///< [m] translations searched each way along x and y
    double angular_window = 0.8;   ///< [rad] rotations searched each way (~45 deg)
    int max_grid_cells = 1024;     ///< cells per side of the grid at most; the cell grows to fit the scan
    std::size_t max_angles = 1441;  ///< rotations searched at most (the step grows beyond)
    /// Share of the best score a candidate loses at `prior_distance` from the initial guess (quadratic
    /// in its distance) and at the angular window's edge: among equally good poses (a corridor) the
    /// nearest wins.
    double prior_weight = 0.05;
    /// [m] distance at which the pull costs prior_weight (0: the linear window). A wider window with
    /// the same prior_distance pulls as hard per metre: it only adds poses, it does not weaken the pull.
    double prior_distance = 0.0;
    /// [cells] sigma of the Gaussian a reference point is rasterized with. A best pose half a cell off
    /// the grid loses exp(-1 / (8 sigma^2)) of its score: 12% at 1 cell, 3% at 2 cells.
    double kernel_sigma_cells = 1.0;
    /// The platform drives along its heading: a candidate also loses prior_weight of the best score at
    /// `prior_distance` off the ray from `heading_origin` along its chord heading (quadratic in that
    /// distance). A candidate with yaw y turned from `heading_yaw` to y, and over a turn a wheeled
    /// platform's sensor moves along the arc's chord: halfway between the two headings. Backward and
    /// sideways poses pay; forward ones, at any distance, do not.
    bool heading_prior = false;
    Eigen::Vector2d heading_origin = Eigen::Vector2d::Zero();  ///< [m] where the ray starts (the last pose)
    double heading_yaw = 0.0;                                  ///< [rad] the last pose's heading
};

struct CorrelativeMatch {
    Eigen::Isometry3d T_world_sensor = Eigen::Isometry3d::Identity();  ///< the initial guess when !valid
    double score = 0.0;        ///< mean likelihood of the points at the best pose, in [0, 1]
    double resolution = 0.0;   ///< [m] cell used
    double angle_step = 0.0;   ///< [rad] rotation step used
    std::size_t points = 0;    ///< scan points searched with
    bool valid = false;        ///< reference and scan points were there to match
    /// The best pose lies on the window's border (translation or rotation): the motion may lie beyond.
    bool at_edge = false;
    bool at_linear_edge = false;   ///< on the translation window's border
    bool at_angular_edge = false;  ///< on the rotation window's border
};

/// The planar pose near `T_initial` (within the windows) that best explains `points_in_sensor` given
/// `reference_in_world` (both: x, y used, z ignored). Deterministic.
CorrelativeMatch MatchCorrelative2D(const std::vector<Eigen::Vector3d>& reference_in_world,
                                    const std::vector<Eigen::Vector3d>& points_in_sensor, const Eigen::Isometry3d& T_initial,
                                    const CorrelativeMatchConfig& config);

}  // namespace revisit
