#pragma once
/// Off-screen OpenGL through OSMesa (no display, no GPU): draws MRPT scenes into cv::Mat.
/// One context per process on its own thread, created on first use and reused (DATA.md: libOSMesa must be linked
/// before libGL).
#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <functional>
#include <memory>
#include <mutex>

namespace mrpt::opengl {
class COpenGLScene;
}

namespace revisit {

/// Where the camera looks from. Azimuth -90 deg with elevation 90 deg is top-down with +y (north) up.
struct CameraView {
    Eigen::Vector3d target = Eigen::Vector3d::Zero();  ///< [m] point looked at
    double distance = 50.0;       ///< [m] eye distance; orthographic: the visible height is distance / 2
    double azimuth_deg = -90.0;   ///< [deg]
    double elevation_deg = 90.0;  ///< [deg]
    bool orthographic = true;
    double fov_deg = 40.0;        ///< [deg] vertical field of view when perspective
};

/// A rendered frame and the projection that made it, so that 2D annotations can be drawn on top.
struct RenderedFrame {
    cv::Mat image;  ///< CV_8UC3, BGR
    Eigen::Matrix4d world_to_clip = Eigen::Matrix4d::Identity();

    /// Pixel position (column, row) of a world point; false when behind the camera.
    bool Project(const Eigen::Vector3d& p_world, cv::Point2d& pixel) const;
};

class OffscreenRenderer {
  public:
    /// The process-wide renderer (OpenGL contexts are expensive and MRPT caches shaders per context).
    static OffscreenRenderer& Instance();

    /// Renders the scene's main viewport. Thread-safe: every call runs on the renderer's own GL thread, one at a
    /// time (MRPT's render state is per thread, so the context never changes threads).
    /// The scene's GL buffers are created on the GL thread and freed where the caller destroys it: prefer the
    /// overload below, which also builds and frees the scene there.
    RenderedFrame Render(const mrpt::opengl::COpenGLScene& scene, const CameraView& view, int width, int height);
    /// Builds a scene with `build_scene`, renders and destroys it, all on the GL thread (any caller thread).
    RenderedFrame Render(const std::function<void(mrpt::opengl::COpenGLScene&)>& build_scene, const CameraView& view,
                         int width, int height);

    ~OffscreenRenderer();
    OffscreenRenderer(const OffscreenRenderer&) = delete;
    OffscreenRenderer& operator=(const OffscreenRenderer&) = delete;

  private:
    OffscreenRenderer();
    RenderedFrame RenderHere(const mrpt::opengl::COpenGLScene& scene, const CameraView& view, int width, int height);
    void Stop();  ///< ends the GL thread after its queued jobs
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace revisit
