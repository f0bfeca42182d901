#include "config/config.hpp"

namespace revisit {
namespace {
using Range = ConfigSchema::Range;

void BindInputAndOdometry(ConfigSchema& s, PipelineConfig& c) {
    s.Add("input.auto_settings", &c.input.auto_settings, "",
          "derive every setting no --config/--set gave from the first scans (ranges, field of view, points per scan); false: the defaults below");
    s.Add("input.follow_scene_scale", &c.input.follow_scene_scale, "",
          "with auto_settings: odometry.max_range follows the scene's 99% range as the sequence unfolds (when not given)");
    s.Add("input.kitti_vertical_correction", &c.input.kitti_vertical_correction, "",
          "rotate KITTI HDL-64E points by 0.205 deg about their azimuth normal (docs/method.md, odometry)");
    s.Add("input.sensor_label", &c.input.sensor_label, "", "rawlogs: use only this sensor label (empty: all); HeLiPR: the LiDAR read, Ouster, Velodyne, Avia or Aeva (empty: Ouster)");
    s.Add("input.topic", &c.input.topic, "", "ROS bags: the PointCloud2 or LaserScan topic (empty: the only one; --topic)");
    s.Add("input.odometry_topic", &c.input.odometry_topic, "",
          "ROS bags: the nav_msgs/Odometry topic giving the odometry prior (empty: the only one; none: no prior)");
    s.Add("input.reference_topic", &c.input.reference_topic, "",
          "ROS bags: PoseStamped, Path or Odometry topic of reference poses (empty: the only PoseStamped/Path; none: none)");
    s.Add("input.laser_aperture_deg", &c.input.laser_aperture_deg, "deg",
          "2D lasers: field of view replacing the file's (0: the file's; radish intel.rawlog needs 180)", Range{0, 360});
    s.Add("input.reference_end_tolerance", &c.input.reference_end_tolerance, "s",
          "TUM reference / --poses files pair with scans by time: a scan this far past their first or last pose takes it (0: half their median spacing)",
          Range{0, 1e6});
    s.Add("input.reference_max_gap", &c.input.reference_max_gap, "s",
          "TUM reference / --poses files: longest gap between two poses interpolated across; a scan in a longer one has no pose (0: 5 x their median spacing)",
          Range{0, 1e6});
    auto& o = c.odometry;
    s.Add("odometry.max_range", &o.max_range, "m", "points beyond are dropped; map radius (KISS-ICP paper-era: 100)", Range{1, 1000});
    s.Add("odometry.min_range", &o.min_range, "m", "points closer are dropped (KISS-ICP paper-era: 5)", Range{0, 100});
    s.Add("odometry.voxel_size", &o.voxel_size, "m", "map voxel; 0 = max_range / 100 (KISS-ICP)", Range{0, 10});
    s.Add("odometry.max_points_per_voxel", &o.max_points_per_voxel, "", "map points per voxel (KISS-ICP: 20)", Range{1, 100});
    s.Add("odometry.initial_threshold", &o.initial_threshold, "m", "adaptive threshold before motion (KISS-ICP: 2.0)", Range{0.01, 100});
    s.Add("odometry.min_motion_th", &o.min_motion_th, "m", "a frame updates the threshold only above this motion (KISS-ICP: 0.1)", Range{0, 10});
    s.AddEnum("odometry.kernel", &o.kernel, {{"paper", IcpKernel::kPaper}, {"later", IcpKernel::kLater}},
              "Geman-McClure scale: paper-era sigma/3, later sigma (docs/method.md, odometry)");
    s.AddEnum("odometry.residual", &o.residual,
              {{"point_to_plane", IcpResidual::kPointToPlane}, {"point_to_point", IcpResidual::kPointToPoint}},
              "point_to_plane: along planar map voxels' normals, planes alone when they fix every translation (data: rings >= 1 deg apart); KISS-ICP's point_to_point");
    s.Add("odometry.max_iterations", &o.max_iterations, "", "ICP iterations per frame (KISS-ICP: 500)", Range{1, 10000});
    s.Add("odometry.convergence", &o.convergence, "", "stop when the update norm is below (KISS-ICP: 1e-4)", Range{1e-12, 1});
    s.Add("odometry.anderson_depth", &o.anderson_depth, "",
          "Anderson acceleration of the ICP over this many previous steps, kept only when the robust cost does not rise; 2: 5-8% less odometry CPU, other poses (0: plain steps, KISS-ICP)", Range{0, 10});
    s.Add("odometry.min_correspondences", &o.min_correspondences, "", "fewer: keep the motion prediction", Range{3, 1000000});
    s.Add("odometry.max_correction", &o.max_correction, "m", "ICP result this far (translation) from the prediction is deemed diverged", Range{0.01, 1000});
    s.Add("odometry.max_correction_factor", &o.max_correction_factor, "",
          "a correction above this x the RMS of earlier corrections (>= one voxel) is a jump: the frame keeps the prediction; 0 = off", Range{0, 1000});
    s.Add("odometry.min_agreement", &o.min_agreement, "",
          "share of a scan's points within a voxel of the map after ICP; fewer: the frame keeps the prediction (garbage, faults)", Range{0, 1});
    s.Add("odometry.turn_hypothesis", &o.turn_hypothesis, "",
          "when the predicted turn moves points by more than a voxel, also register without it and keep the better (swaying sensors)");
    s.Add("odometry.ring_start", &o.ring_start, "",
          "3D: point-to-plane until the motion is measured (a spinning sensor's ground rings pull a moving start to standing still)");
    s.Add("odometry.correlative_start", &o.correlative_start, "",
          "2D lasers: start the ICP from a correlative scan match (every frame without wheel odometry; with it, frames whose ICP failed)");
    s.Add("odometry.correlative_window", &o.correlative_window, "m", "translations the correlative match searches each way", Range{0.01, 100});
    s.Add("odometry.correlative_angular_window_deg", &o.correlative_angular_window_deg, "deg", "rotations the correlative match searches each way", Range{0, 180});
    s.Add("odometry.correlative_heading_prior", &o.correlative_heading_prior, "",
          "2D lasers without wheel odometry: the correlative match prefers poses along the platform's heading (a wheeled platform drives forward; a corridor's aliases lie behind and beside)");
    s.Add("odometry.map_travel_horizon", &o.map_travel_horizon, "m",
          "the map keeps only voxels a scan saw within this much travel, so a scan registers to the scans just before and not to a drifted earlier pass (0 = every voxel within range, KISS-ICP)",
          Range{0, 1e6});
    s.Add("odometry.recent_travel_check", &o.recent_travel_check, "",
          "2D lasers without wheel odometry: also register each frame to the voxels seen within the last max_range of travel, and keep that pose when it explains the scan clearly better there (a drifted earlier pass pulled the frame)");
    s.Add("odometry.beam_check", &o.beam_check, "",
          "2D lasers without wheel odometry: a correlative match over twice the windows wins only when it puts no clearly more returns where earlier beams passed, or beams through mapped walls, than the first match (a room turned by 90 deg)");
    s.Add("odometry.deskew", &o.deskew, "", "constant-velocity motion compensation (paper-era: off)");
    s.Add("odometry.azimuth_clockwise", &o.azimuth_clockwise, "", "deskew without point times: sweep direction (KITTI: clockwise)");
    s.Add("odometry.planar", &o.planar, "", "estimate x, y, yaw only (2D lasers)");
    s.Add("odometry.use_prior", &o.use_prior, "", "use wheel odometry increments as the initial guess when present");
    s.Add("odometry.prior_bias_correction", &o.prior_bias_correction, "",
          "remove the prior's rotation bias per metre, measured against the registered increments (ICP keeps a share of a prior's turn error)");
    s.Add("odometry.prior_bias_window", &o.prior_bias_window, "m", "travel per block of the prior's bias estimate (the mean of the last 8 blocks, when they agree)", Range{0.1, 1e6});
    s.Add("odometry.degenerate_thickness", &o.degenerate_thickness, "m", "points within this of a plane/line: degenerate frame", Range{0, 10});
}

void BindMapsAndImages(ConfigSchema& s, PipelineConfig& c) {
    auto& m = c.local_map;
    s.Add("local_map.voxel_size", &m.voxel_size, "m", "v_map (paper: 1.0; 0.5 for small-FOV sensors)", Range{0.01, 10});
    s.Add("local_map.max_points_per_voxel", &m.max_points_per_voxel, "", "points kept per voxel (paper: 20)", Range{1, 1000});
    s.Add("local_map.split_distance", &m.split_distance, "m", "tau_m: close a map after this distance (paper: 100)", Range{0.5, 100000});
    s.Add("local_map.straight_line_split", &m.straight_line_split, "", "later code: straight-line distance from the first pose (paper: travelled)");
    s.Add("local_map.carry_over", &m.carry_over, "", "later code: points near the new origin seed the next map (paper: off)");
    s.Add("local_map.carry_radius", &m.carry_radius, "m", "carry-over radius (the sensor's max range)", Range{0, 1000});
    s.Add("local_map.max_extent", &m.max_extent, "m",
          "also close a map when the sensor is this far (straight line) from its first pose, so a walk that "
          "returns within one map's travel meets its past in another map (0 = off)", Range{0, 100000});
    auto& d = c.detector.density;
    s.Add("density.resolution", &d.resolution, "m/px", "nu_res (paper: 0.5)", Range{0.005, 10});
    s.Add("density.min_density", &d.min_density, "", "cells below this are zeroed (paper: 0.05)", Range{0, 1});
    s.AddEnum("density.threshold", &d.threshold,
              {{"fraction_of_max", DensityThreshold::kFractionOfMax}, {"byte_scale", DensityThreshold::kByteScale}},
              "what min_density is compared with: paper text (fraction of max) or paper-era code (0-255 scale)");
    s.AddEnum("density.scaling", &d.scaling, {{"min_max", DensityScaling::kMinMax}, {"percentile", DensityScaling::kPercentile}},
              "count to intensity: paper min-max, or a robust percentile (docs/method.md, density image)");
    s.Add("density.scale_percentile", &d.scale_percentile, "", "percentile scaling: this quantile maps to 255", Range{0.5, 1});
    s.Add("density.elevation_instead", &d.elevation_instead, "", "ablation: max height per cell instead of counts");
    s.Add("density.target_extent_pixels", &d.target_extent_pixels, "px", "resolution from the map extent; 0 = fixed", Range{0, 100000});
    s.Add("density.min_resolution", &d.min_resolution, "m/px", "bound of the adaptive resolution", Range{0.005, 10});
    s.Add("density.max_resolution", &d.max_resolution, "m/px", "bound of the adaptive resolution", Range{0.005, 10});
    s.Add("density.max_image_side", &d.max_image_side, "px", "guard against huge images", Range{16, 100000});
    auto& g = c.detector.ground;
    s.Add("ground.enabled", &c.detector.align_ground, "", "level each map on its ground plane (later code)");
    s.Add("ground.cell_size", &g.cell_size, "m", "lowest point per cell is a ground candidate", Range{0.05, 100});
    s.Add("ground.inlier_distance", &g.inlier_distance, "m", "final gate to the plane", Range{0.001, 10});
    s.Add("ground.max_tilt_deg", &g.max_tilt_deg, "deg", "reject planes tilted more", Range{0, 90});
    s.Add("ground.min_ground_points", &g.min_ground_points, "", "fewer candidates: no levelling", Range{3, 1000000});
    s.Add("ground.iterations", &g.iterations, "", "reweighting rounds", Range{1, 100});
}

void BindFeaturesAndMatching(ConfigSchema& s, PipelineConfig& c) {
    auto& f = c.detector.features;
    s.Add("features.max_features", &f.max_features, "", "ORB nfeatures (paper: 500)", Range{1, 100000});
    s.Add("features.edge_threshold", &f.edge_threshold, "px", "ORB edgeThreshold (paper: 31)", Range{1, 255});
    s.Add("features.patch_size", &f.patch_size, "px", "ORB patchSize (paper: 31)", Range{2, 255});
    s.Add("features.wta_k", &f.wta_k, "", "ORB WTA_K (paper: 2)", Range{2, 4});
    s.Add("features.fast_threshold", &f.fast_threshold, "", "FAST threshold on 0-255 (paper: 35)", Range{1, 255});
    s.Add("features.harris_score", &f.harris_score, "", "HARRIS score (later code) instead of FAST (paper)");
    s.Add("features.min_keypoints", &f.min_keypoints, "", "adaptive budget: lower the FAST threshold below this many keypoints; 0 = off", Range{0, 100000});
    s.Add("features.min_fast_threshold", &f.min_fast_threshold, "", "floor of the adaptive FAST threshold", Range{1, 255});
    s.Add("features.pad_border", &f.pad_border, "", "pad images so structure near the border gets keypoints");
    s.Add("features.self_similar_distance", &f.self_similar_distance, "bits", "later code: drop self-similar query descriptors (35); 0 = off", Range{0, 256});
    auto& t = c.detector.tree;
    s.Add("tree.leaf_capacity", &t.leaf_capacity, "", "HBST leaf size (100)", Range{1, 100000});
    s.Add("tree.split_tolerance", &t.split_tolerance, "", "split only when the best bit is this close to 0.5 (0.1)", Range{0, 0.5});
    s.Add("tree.max_distance", &t.max_distance, "bits", "a match needs a smaller Hamming distance (paper: 50)", Range{1, 257});
    auto& d = c.detector;
    s.AddEnum("detector.selection", &d.selection, {{"top_half", CandidateSelection::kTopHalf}, {"all_above_min", CandidateSelection::kAllAboveMin}},
              "candidates: paper top half by votes, or later code all maps with enough matches");
    s.Add("detector.min_candidates", &d.min_candidates, "", "beyond the paper: the top half keeps at least this many maps (1: the paper's rule)", Range{1, 100000});
    s.Add("detector.min_matches", &d.min_matches, "", "matches a candidate needs (paper: 25; small FOV 10; later 3)", Range{1, 100000});
    s.Add("detector.skip_recent_maps", &d.skip_recent_maps, "", "never compare with the last maps (paper: 3)", Range{0, 100000});
    s.Add("detector.skip_recent_travel", &d.skip_recent_travel, "m", "beyond the paper: skip by travelled distance instead; 0 = by count", Range{0, 1e6});
    s.Add("detector.inlier_pixels", &d.inlier_pixels, "px", "RANSAC inlier gate (paper: 3)", Range{0.1, 100});
    s.Add("detector.min_inliers", &d.min_inliers, "", "gamma: accept with this many inliers (paper: 10; later 6)", Range{2, 100000});
    s.Add("detector.rematch", &d.rematch, "", "beyond the paper: RANSAC on every mutual best descriptor match with the candidate, not only the tree's one-leaf matches");
    s.Add("detector.rank_by_nearest", &d.rank_by_nearest, "", "beyond the paper: the top half ranked by the votes of each query descriptor's nearest match, not by every map's best in its leaf");
    s.Add("detector.store_images", &d.store_images, "", "keep density images in the database (reports, persistence)");
    auto& r = c.detector.ransac;
    s.AddEnum("ransac.sampling", &r.sampling, {{"exhaustive", RansacSampling::kExhaustive}, {"random", RansacSampling::kRandom}},
              "every distinct pair once, best matches first; or seeded random draws (paper-era, later code)");
    s.Add("ransac.max_trials", &r.max_trials, "", "cap on hypotheses; 0 = all pairs (exhaustive) or n(n-1) draws (random); later code 688", Range{0, 10000000});
    s.Add("ransac.early_stop_inliers", &r.early_stop_inliers, "", "stop at this many inliers (30)", Range{2, 100000});
    s.Add("ransac.weighted_sampling", &r.weighted_sampling, "", "paper-era: prefer matches of small descriptor distance");
    s.Add("ransac.refit_inliers", &r.refit_inliers, "", "later code: final fit on the inliers");
    s.Add("ransac.seed", &c.detector.ransac.seed, "", "random seed of random sampling (every random choice derives from it)");
}

void BindRefinementAndGraph(ConfigSchema& s, PipelineConfig& c) {
    auto& r = c.refinement;
    s.Add("refinement.voxel_size", &r.voxel_size, "m", "downsampling of both maps", Range{0.01, 10});
    s.Add("refinement.normal_radius", &r.normal_radius, "m", "neighbourhood of the normals", Range{0.05, 20});
    s.Add("refinement.initial_max_distance", &r.initial_max_distance, "m", "correspondence gate at the start", Range{0.01, 100});
    s.Add("refinement.vertical_search", &r.vertical_search, "m",
          "before ICP, try offsets along the vertical within +-this (a 2D closure knows no height; 0 = off)", Range{0, 100});
    s.Add("refinement.max_correspondence_distance", &r.max_correspondence_distance, "m", "final gate (paper: ~0.9)", Range{0.01, 100});
    s.Add("refinement.loss_scale", &r.loss_scale, "m", "Cauchy scale of the point-to-plane residual", Range{0.001, 100});
    s.Add("refinement.max_iterations", &r.max_iterations, "", "outer ICP iterations", Range{1, 1000});
    s.Add("refinement.min_overlap", &r.min_overlap, "", "accept above this voxel overlap (KISS-SLAM: 0.4)", Range{0, 1});
    s.Add("refinement.min_correspondences", &r.min_correspondences, "", "accept with at least this many", Range{0, 10000000});
    s.Add("refinement.max_rms", &r.max_rms, "m", "accept below this residual RMS", Range{0.001, 100});
    s.Add("refinement.smear_gate_factor", &r.smear_gate_factor, "",
          "the default RMS gate rises to this multiple of the median RMS of each map registered onto its predecessor (0: max_rms alone)",
          Range{0, 100});
    s.Add("refinement.information_effective_points", &r.information_effective_points, "",
          "a closure's registration information counts its correspondences as this many independent points (<= 0: all)",
          Range{-1, 1e9});
    s.Add("refinement.min_free_space_agreement", &r.min_free_space_agreement, "",
          "2D lasers: a pair below min_overlap is accepted when its walls agree with the other map's observations at least this share, both ways (0 = off)",
          Range{0, 1});
    s.Add("refinement.max_correction_translation", &r.max_correction_translation, "m", "reject refinements this far from the 2D guess", Range{0, 1000});
    s.Add("refinement.max_correction_rotation", &r.max_correction_rotation, "rad", "same, rotation", Range{0, 3.2});
    s.AddEnum("graph.loop_loss", &c.graph.loop_loss,
              {{"none", RobustLossKind::kNone}, {"cauchy", RobustLossKind::kCauchy}, {"dcs", RobustLossKind::kDynamicCovarianceScaling}},
              "robust loss of closure edges");
    s.Add("graph.loop_loss_scale", &c.graph.loop_loss_scale, "", "kernel scale on chi^2", Range{1e-6, 1e9});
    s.Add("graph.loop_tolerance_chi2", &c.graph.loop_tolerance_chi2, "",
          "a closure edge costs nothing while its chi^2 is within this: it does not pull odometry that already agrees with it (0 = off)",
          Range{0, 1e6});
    s.Add("graph.anneal", &c.graph.anneal, "", "graduated robustness: wide kernel first, so true closures far from drifted odometry still pull");
    s.Add("graph.max_iterations", &c.graph.max_iterations, "", "Ceres iterations per stage", Range{1, 100000});
    auto& n = c.graph_noise;
    s.Add("graph.odometry_translation_per_m", &n.odometry_translation_per_m, "m/m",
          "odometry edge sigma per metre travelled (1%; cautious: a robust loss rejects true closures if too small)", Range{1e-6, 1});
    s.Add("graph.odometry_rotation_per_m", &n.odometry_rotation_per_m, "rad/m", "odometry rotation sigma per metre (3e-4)", Range{1e-8, 1});
    s.Add("graph.closure_information_from_registration", &n.closure_information_from_registration, "", "closure information from the 3D registration");
    s.Add("graph.closure_sigma_translation", &n.closure_sigma_translation, "m", "fixed closure noise (paper: 1e3 x identity)", Range{1e-6, 100});
    s.Add("graph.closure_sigma_rotation", &n.closure_sigma_rotation, "rad", "fixed closure noise", Range{1e-6, 10});
    s.Add("graph.optimize_every_closures", &n.optimize_every_closures, "", "online re-optimization period (accepted closures; at least a tenth of those in the graph)", Range{1, 100000});
    s.Add("graph.online_time_budget", &n.online_time_budget, "s", "time bound per online update", Range{0.001, 1000});
    s.Add("graph.min_weight", &n.min_weight, "", "closures ending below this robust weight are rejected as inconsistent (0 = keep all)", Range{0, 1});
    auto& pcm = c.consistency;
    s.Add("consistency.enabled", &pcm.enabled, "",
          "keep only the largest set of pairwise-consistent verified closures before the pose graph (PCM)");
    s.Add("consistency.chi2_threshold", &pcm.chi2_threshold, "",
          "two closures agree when their cycle with the odometry has chi^2 below this (99% of chi^2, 6 dof: 16.81)", Range{0.01, 1e9});
    s.Add("consistency.odometry_chi2_threshold", &pcm.odometry_chi2_threshold, "",
          "a closure alone is dropped when its cycle with the odometry has chi^2 above this (99.99% of chi^2, 6 dof: 27.86)",
          Range{0.01, 1e9});
    s.Add("consistency.closure_sigma_translation", &pcm.closure_sigma_translation, "m", "error of one verified closure", Range{1e-4, 100});
    s.Add("consistency.closure_sigma_rotation_deg", &pcm.closure_sigma_rotation_deg, "deg", "same, rotation", Range{1e-4, 180});
    s.Add("consistency.exact_max_steps", &pcm.exact_max_steps, "",
          "maximum-clique search budget (exact below it; past it the best set found is kept)", Range{1, 1000000000});
    s.Add("consistency.calibrate_drift", &pcm.calibrate_drift, "",
          "at the end, lower graph.odometry_rotation_per_m to calibration_factor x the largest rotation drift per metre "
          "of the consistent closures (never raise it; skipped when the rate is given explicitly) and check them again");
    s.Add("consistency.calibration_min_closures", &pcm.calibration_min_closures, "",
          "consistent closures needed before their drift is trusted", Range{1, 1000000});
    s.Add("consistency.calibration_factor", &pcm.calibration_factor, "", "margin over the largest measured drift", Range{1, 1000});
    s.Add("consistency.calibration_min_rotation_per_m", &pcm.calibration_min_rotation_per_m, "rad/m",
          "the calibrated rate never goes below this (the 3D default rate)", Range{0, 1});
    auto& prox = c.proximity;
    s.Add("proximity.enabled", &prox.enabled, "",
          "after the final optimization, register maps the corrected poses lay over each other (docs/method.md: at the end of the run)");
    s.Add("proximity.rounds", &prox.rounds, "", "passes, each from the estimate the previous one improved", Range{0, 100});
    s.Add("proximity.min_overlap", &prox.min_overlap, "",
          "predicted share of the smaller map's ground cells (1/20 of a map length) from which a pair is registered", Range{0, 1});
    s.Add("proximity.max_per_map", &prox.max_per_map, "", "registrations per map and round, largest predicted overlap first", Range{0, 100000});
    s.Add("proximity.revisit_detour", &prox.revisit_detour, "",
          "non-consecutive maps of one session are registered only when the path between them is at least this many "
          "times the straight line, or their scans meet (0: every overlaid pair)",
          Range{0, 1000});
    s.Add("proximity.odometry_check_below", &prox.odometry_check_below, "",
          "with fewer consistent detector closures, first register the maps the odometry overlays; they may displace "
          "the detector's (0: never)",
          Range{0, 100000});
}

void BindEvaluationAndOutput(ConfigSchema& s, PipelineConfig& c) {
    auto& g = c.ground_truth;
    s.Add("evaluation.segment_length", &g.segment_length, "m", "ground-truth segments (paper: 2)", Range{0.01, 1000});
    s.Add("evaluation.voxel_size", &g.voxel_size, "m", "overlap voxels (0.5)", Range{0.01, 100});
    s.Add("evaluation.min_overlap", &g.min_overlap, "", "a closure above this overlap (0.5)", Range{0, 1});
    s.Add("evaluation.max_range", &g.max_range, "m", "segments farther apart are skipped (sensor range)", Range{0.1, 10000});
    s.Add("evaluation.travel_gap_ranges", &g.travel_gap_ranges, "", "later segment >= this x max_range of travel after (2)", Range{0, 1000});
    s.Add("evaluation.min_travel", &g.min_travel, "m", "later segment >= this much travel after; 0 = travel_gap_ranges x max_range (paper: 200)", Range{0, 1e7});
    s.Add("evaluation.tau_d", &c.predicted.max_distance, "m",
          "a map closure predicts its scan pairs closer than this; 0: from the data, the distance within which "
          "the ground truth's revisit segment pairs mostly overlap (the paper's is 6)",
          Range{0, 1000});
    s.Add("evaluation.planar", &c.predicted.planar, "", "distances in x, y only");
    auto& t = c.truth;
    s.Add("evaluation.true_translation", &t.true_translation, "m", "an accepted closure is true within this error against the reference", Range{0, 1000});
    s.Add("evaluation.true_rotation_deg", &t.true_rotation_deg, "deg", "and this yaw error", Range{0, 180});
    s.Add("evaluation.revisit_radius", &t.revisit_radius, "m", "revisit coverage: a scan this close to an earlier one revisits it", Range{0, 10000});
    s.Add("evaluation.revisit_gap", &t.revisit_gap, "m", "revisit coverage: of travel at least between the two", Range{0, 1e7});
    auto& sc = c.scan_context;
    s.Add("scan_context.max_radius", &sc.max_radius, "m", "descriptor radius (80)", Range{1, 1000});
    s.Add("scan_context.sensor_height", &sc.sensor_height, "m", "added to z (2.0)", Range{-100, 100});
    s.Add("scan_context.num_candidates", &sc.num_candidates, "", "ring-key candidates per query (10)", Range{1, 1000});
    auto& o = c.output;
    s.Add("output.map_voxel", &o.map_voxel, "m", "local maps stored in the run folder", Range{0.01, 100});
    s.Add("output.global_map_voxel", &o.global_map_voxel, "m", "corrected global map (PLY)", Range{0.01, 100});
    s.Add("output.global_map_max_points", &o.global_map_max_points, "",
          "corrected global map: past this many points its voxel doubles until it fits (0: no cap; not when global_map_voxel is given)",
          Range{0, 1e9});
    s.Add("output.write_report", &o.write_report, "", "render report/index.html");
    s.Add("output.report_candidates", &o.report_candidates, "",
          "report pages for the strongest candidates below the acceptance threshold (others: table rows)", Range{0, 1e6});
    s.Add("output.report_closure_pages", &o.report_closure_pages, "",
          "report pages for closures that reached the threshold: the worst, the best, a sample (false ones besides)", Range{0, 1e6});
    s.Add("output.report_map_pages", &o.report_map_pages, "", "report pages for at most this many local maps (those of the closure pages)", Range{0, 1e6});
    s.Add("output.scan_context", &o.scan_context, "", "run the ScanContext baseline when ground truth exists");
    s.Add("output.elevation_ablation", &o.elevation_ablation, "", "score the elevation-image ablation when ground truth exists");
    auto& g2 = c.occupancy;
    s.Add("occupancy.resolution", &g2.resolution, "m", "occupancy grid cell; 0 = 0.05 for 2D lasers, output.map_voxel for 3D", Range{0, 100});
    s.Add("occupancy.max_cells_per_side", &g2.max_cells_per_side, "", "a larger extent doubles the cell until it fits", Range{16, 65536});
    s.Add("occupancy.occupied_share", &g2.occupied_share, "", "a cell that ends this share of the rays reaching it is occupied", Range{0.01, 1});
    s.Add("occupancy.min_height", &g2.min_height, "m", "3D: lowest obstacle above the levelled ground", Range{-100, 100});
    s.Add("occupancy.max_height", &g2.max_height, "m", "3D: highest obstacle above the levelled ground", Range{-100, 1000});
    s.Add("occupancy.ground_tolerance", &g2.ground_tolerance, "m", "3D: points this close to the ground make a cell free", Range{0, 10});
    s.Add("occupancy.ground_cell", &g2.ground_cell, "m", "3D: the ground is the lowest point within one such cell", Range{0.05, 100});
}

void BindFleet(ConfigSchema& s, PipelineConfig& c) {
    auto& f = c.fleet;
    s.Add("fleet.min_cross_closures", &f.min_cross_closures, "",
          "merge: consistent cross-session closures needed to join two sessions", Range{1, 1000});
    s.Add("fleet.slurm_cpus_per_task", &f.slurm_cpus_per_task, "", "batch --engine slurm: CPUs of each run task", Range{1, 1024});
    s.Add("fleet.slurm_memory_mb", &f.slurm_memory_mb, "MiB", "batch --engine slurm: memory of each task", Range{64, 1e7});
    s.Add("fleet.slurm_time_minutes", &f.slurm_time_minutes, "min", "batch --engine slurm: time limit of each task", Range{1, 1e6});
    s.Add("fleet.slurm_partition", &f.slurm_partition, "", "batch --engine slurm: partition (empty: the cluster's default)");
}

}  // namespace

ConfigSchema MakeConfigSchema(PipelineConfig& config) {
    ConfigSchema schema;
    BindInputAndOdometry(schema, config);
    BindMapsAndImages(schema, config);
    BindFeaturesAndMatching(schema, config);
    BindRefinementAndGraph(schema, config);
    BindEvaluationAndOutput(schema, config);
    BindFleet(schema, config);
    return schema;
}

PipelineConfig LoadConfig(const std::vector<std::string>& files, const std::vector<std::string>& overrides) {
    PipelineConfig config;
    auto schema = MakeConfigSchema(config);
    for (const auto& file : files) schema.ApplyFile(file);
    for (const auto& assignment : overrides) schema.ApplyOverride(assignment);
    config.explicit_keys = schema.assigned();
    return config;
}

ReaderOptions MakeReaderOptions(const InputConfig& input) {
    ReaderOptions options;
    options.sensor_label = input.sensor_label;
    options.kitti_vertical_correction = input.kitti_vertical_correction;
    options.laser_aperture = input.laser_aperture_deg * M_PI / 180.0;
    options.points_topic = input.topic;
    options.odometry_topic = input.odometry_topic;
    options.reference_topic = input.reference_topic;
    options.pose_pairing.end_tolerance = input.reference_end_tolerance;
    options.pose_pairing.max_gap = input.reference_max_gap;
    return options;
}

std::string DumpConfig(const PipelineConfig& config) {
    PipelineConfig copy = config;
    return MakeConfigSchema(copy).Dump();
}

}  // namespace revisit
