#include "render/offscreen_renderer.hpp"

#include <Eigen/Geometry>
#include <GL/osmesa.h>
#include <mrpt/img/CImage.h>
#include <mrpt/opengl/CFBORender.h>
#include <mrpt/opengl/COpenGLScene.h>
#include <mrpt/opengl/TRenderMatrices.h>

#include <opencv2/imgproc.hpp>

#include <map>
#include <stdexcept>
#include <utility>
#include <vector>

namespace revisit {

struct OffscreenRenderer::Impl {
    OSMesaContext context = nullptr;
    std::vector<unsigned char> dummy_buffer;  // OSMesa needs a default framebuffer; MRPT draws into its own FBO
    std::map<std::pair<int, int>, std::unique_ptr<mrpt::opengl::CFBORender>> fbos;
};

bool RenderedFrame::Project(const Eigen::Vector3d& p_world, cv::Point2d& pixel) const {
    const Eigen::Vector4d clip = world_to_clip * p_world.homogeneous();
    if (clip.w() <= 1e-9) return false;
    const double x_ndc = clip.x() / clip.w();
    const double y_ndc = clip.y() / clip.w();
    pixel.x = (x_ndc + 1.0) * 0.5 * image.cols;
    pixel.y = (1.0 - y_ndc) * 0.5 * image.rows;  // image rows grow downwards
    return true;
}

OffscreenRenderer& OffscreenRenderer::Instance() {
    static OffscreenRenderer renderer;
    return renderer;
}

OffscreenRenderer::OffscreenRenderer() : impl_(std::make_unique<Impl>()) {
    // A 3.3 core profile: MRPT 2.5's shaders need it; llvmpipe gives 4.5 core (DATA.md).
    const int attributes[] = {OSMESA_FORMAT, OSMESA_RGBA, OSMESA_DEPTH_BITS, 24, OSMESA_PROFILE, OSMESA_CORE_PROFILE,
                              OSMESA_CONTEXT_MAJOR_VERSION, 3, OSMESA_CONTEXT_MINOR_VERSION, 3, 0};
    impl_->context = OSMesaCreateContextAttribs(attributes, nullptr);
    if (impl_->context == nullptr) throw std::runtime_error("render: cannot create an OSMesa OpenGL 3.3 core context");
    impl_->dummy_buffer.assign(16 * 16 * 4, 0);
}

OffscreenRenderer::~OffscreenRenderer() {
    if (impl_->context == nullptr) return;
    OSMesaMakeCurrent(impl_->context, impl_->dummy_buffer.data(), GL_UNSIGNED_BYTE, 16, 16);
    impl_->fbos.clear();  // framebuffers are freed while their context is current
    OSMesaDestroyContext(impl_->context);
}

RenderedFrame OffscreenRenderer::Render(const mrpt::opengl::COpenGLScene& scene, const CameraView& view, int width,
                                        int height) {
    if (width <= 0 || height <= 0) throw std::invalid_argument("render: image size must be positive");
    std::lock_guard<std::mutex> lock(mutex_);
    if (!OSMesaMakeCurrent(impl_->context, impl_->dummy_buffer.data(), GL_UNSIGNED_BYTE, 16, 16))
        throw std::runtime_error("render: OSMesaMakeCurrent failed");

    auto& fbo = impl_->fbos[{width, height}];
    if (!fbo) {
        mrpt::opengl::CFBORender::Parameters parameters(static_cast<unsigned>(width), static_cast<unsigned>(height));
        parameters.create_EGL_context = false;  // render into the OSMesa context made current above
        fbo = std::make_unique<mrpt::opengl::CFBORender>(parameters);
    }
    auto& camera = fbo->getCamera(scene);
    camera.setOrthogonal(view.orthographic);
    if (!view.orthographic) camera.setProjectiveFOVdeg(static_cast<float>(view.fov_deg));
    camera.setPointingAt(static_cast<float>(view.target.x()), static_cast<float>(view.target.y()),
                         static_cast<float>(view.target.z()));
    camera.setZoomDistance(static_cast<float>(view.distance));
    camera.setAzimuthDegrees(static_cast<float>(view.azimuth_deg));
    camera.setElevationDegrees(static_cast<float>(view.elevation_deg));

    mrpt::img::CImage rgb;
    fbo->render_RGB(scene, rgb);

    RenderedFrame frame;
    rgb.asCvMat(frame.image, mrpt::img::DEEP_COPY);
    if (frame.image.channels() == 1) cv::cvtColor(frame.image, frame.image, cv::COLOR_GRAY2BGR);
    // MRPT keeps the matrices of the last render of the viewport (pmv is per object: compose P * V here).
    const auto matrices = scene.getViewport()->getRenderMatrices();
    const Eigen::Matrix4d P = matrices.p_matrix.asEigen().cast<double>();
    const Eigen::Matrix4d V = matrices.v_matrix.asEigen().cast<double>();
    frame.world_to_clip = P * V;
    return frame;
}

}  // namespace revisit
