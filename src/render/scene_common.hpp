#pragma once
/// Pieces shared by the 3D pictures: coloured clouds, framing, and the annotations that make a view readable.
#include "render/annotate.hpp"
#include "render/offscreen_renderer.hpp"
#include "render/palette.hpp"

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <mrpt/opengl/COpenGLScene.h>
#include <vector>

namespace revisit {

struct RenderConfig {
    int width = 1280;                ///< [pixels]
    int height = 960;                ///< [pixels]
    double point_size = 2.0;         ///< [pixels]
    int line_thickness = 3;          ///< [pixels] trajectories
    double margin = 0.08;            ///< free border around the content [fraction of the extent]
    double oblique_elevation_deg = 35.0;  ///< [deg] camera elevation of oblique views
    double oblique_azimuth_deg = -60.0;   ///< [deg]
    double fov_deg = 40.0;           ///< [deg] vertical field of view of oblique views
    std::size_t max_points = 1500000;     ///< clouds above this are decimated by a fixed stride (deterministic)
};

/// Axis-aligned box of everything that must be visible.
struct Extent {
    Eigen::Vector3d min = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
    Eigen::Vector3d max = Eigen::Vector3d::Constant(-std::numeric_limits<double>::infinity());
    void Add(const Eigen::Vector3d& p) { min = min.cwiseMin(p); max = max.cwiseMax(p); }
    bool Empty() const { return !(min.x() <= max.x()); }
};

/// Height range [z_low, z_high] from the 2nd and 98th percentiles (robust to a few stray points).
Eigen::Vector2d RobustHeightRange(const std::vector<Eigen::Vector3f>& points);

/// Adds a cloud coloured by height (palette HeightColor) to the scene.
void AddHeightColoredCloud(mrpt::opengl::COpenGLScene& scene, const std::vector<Eigen::Vector3f>& points_world,
                           const RenderConfig& config);

/// Adds a cloud in one colour, transformed by T_world_points.
void AddUniformCloud(mrpt::opengl::COpenGLScene& scene, const std::vector<Eigen::Vector3f>& points,
                     const Eigen::Isometry3d& T_world_points, Rgb color, const RenderConfig& config);

/// Camera that frames the extent: top-down orthographic (north up) or oblique perspective.
CameraView FrameExtent(const Extent& extent, bool oblique, const RenderConfig& config);

/// Adds a faint ground grid over the extent at height `z` [m] with a round spacing; returns the spacing [m].
double AddGroundGrid(mrpt::opengl::COpenGLScene& scene, const Extent& extent, double z);

/// Height for the ground grid: the low robust height of the points (stray points below the ground are ignored),
/// or the bottom of the extent without points.
double GroundHeight(const std::vector<Eigen::Vector3f>& points, const Extent& extent);

/// Projects a 3D polyline into the frame (points behind the camera are dropped).
Polyline2d ProjectPolyline(const RenderedFrame& frame, const std::vector<Eigen::Vector3d>& points_world);

/// Scale bar and north arrow for top-down views, axes glyph for oblique views (measured from the projection).
void AnnotateOrientation(RenderedFrame& frame, const Eigen::Vector3d& centre_world, bool oblique);

}  // namespace revisit
