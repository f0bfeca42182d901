#include "render/offscreen_renderer.hpp"

#include <Eigen/Geometry>
#include <GL/osmesa.h>
#include <mrpt/img/CImage.h>
#include <mrpt/opengl/CFBORender.h>
#include <mrpt/opengl/COpenGLScene.h>
#include <mrpt/opengl/TRenderMatrices.h>

#include <opencv2/imgproc.hpp>

#include <condition_variable>
#include <deque>
#include <functional>
#include <future>
#include <map>
#include <thread>
#include <stdexcept>
#include <utility>
#include <vector>

namespace revisit {

/// The context and every GL call live on one thread of their own: MRPT keeps per-thread render state, so a
/// context shared by worker threads fails (CFBORender asserts) even when the calls are serialized.
struct OffscreenRenderer::Impl {
    OSMesaContext context = nullptr;
    std::vector<unsigned char> dummy_buffer;  // OSMesa needs a default framebuffer; MRPT draws into its own FBO
    std::map<std::pair<int, int>, std::unique_ptr<mrpt::opengl::CFBORender>> fbos;

    std::thread gl_thread;
    std::mutex queue_mutex;
    std::condition_variable queue_changed;
    std::deque<std::function<void()>> jobs;
    bool stopping = false;

    void Loop() {
        for (;;) {
            std::function<void()> job;
            {
                std::unique_lock<std::mutex> lock(queue_mutex);
                queue_changed.wait(lock, [&] { return stopping || !jobs.empty(); });
                if (jobs.empty()) return;  // stopping, nothing left
                job = std::move(jobs.front());
                jobs.pop_front();
            }
            job();
        }
    }

    /// Runs `work` on the GL thread and returns its result (or rethrows its exception) to the caller.
    template <typename Result>
    Result RunOnGlThread(std::function<Result()> work) {
        auto task = std::make_shared<std::packaged_task<Result()>>(std::move(work));
        std::future<Result> result = task->get_future();
        {
            std::lock_guard<std::mutex> lock(queue_mutex);
            jobs.emplace_back([task] { (*task)(); });
        }
        queue_changed.notify_one();
        return result.get();
    }
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
    impl_->gl_thread = std::thread([impl = impl_.get()] { impl->Loop(); });
    try {
        impl_->RunOnGlThread<bool>([impl = impl_.get()] {
            // A 3.3 core profile: MRPT 2.5's shaders need it; llvmpipe gives 4.5 core (DATA.md).
            const int attributes[] = {OSMESA_FORMAT, OSMESA_RGBA, OSMESA_DEPTH_BITS, 24, OSMESA_PROFILE, OSMESA_CORE_PROFILE,
                                      OSMESA_CONTEXT_MAJOR_VERSION, 3, OSMESA_CONTEXT_MINOR_VERSION, 3, 0};
            impl->context = OSMesaCreateContextAttribs(attributes, nullptr);
            if (impl->context == nullptr) throw std::runtime_error("render: cannot create an OSMesa OpenGL 3.3 core context");
            impl->dummy_buffer.assign(16 * 16 * 4, 0);
            return true;
        });
    } catch (...) {
        Stop();
        throw;
    }
}

void OffscreenRenderer::Stop() {
    {
        std::lock_guard<std::mutex> lock(impl_->queue_mutex);
        impl_->stopping = true;
    }
    impl_->queue_changed.notify_one();
    if (impl_->gl_thread.joinable()) impl_->gl_thread.join();
}

OffscreenRenderer::~OffscreenRenderer() {
    if (impl_->context != nullptr) {
        impl_->RunOnGlThread<bool>([impl = impl_.get()] {
            OSMesaMakeCurrent(impl->context, impl->dummy_buffer.data(), GL_UNSIGNED_BYTE, 16, 16);
            impl->fbos.clear();  // framebuffers are freed while their context is current
            OSMesaDestroyContext(impl->context);
            return true;
        });
    }
    Stop();
}

RenderedFrame OffscreenRenderer::Render(const mrpt::opengl::COpenGLScene& scene, const CameraView& view, int width,
                                        int height) {
    if (width <= 0 || height <= 0) throw std::invalid_argument("render: image size must be positive");
    // Callers on any thread wait for their turn on the GL thread (the caller's scene lives until it returns).
    return impl_->RunOnGlThread<RenderedFrame>([&] { return RenderHere(scene, view, width, height); });
}

RenderedFrame OffscreenRenderer::Render(const std::function<void(mrpt::opengl::COpenGLScene&)>& build_scene,
                                        const CameraView& view, int width, int height) {
    if (width <= 0 || height <= 0) throw std::invalid_argument("render: image size must be positive");
    return impl_->RunOnGlThread<RenderedFrame>([&] {
        mrpt::opengl::COpenGLScene scene;
        build_scene(scene);
        return RenderHere(scene, view, width, height);
    });
}

RenderedFrame OffscreenRenderer::RenderHere(const mrpt::opengl::COpenGLScene& scene, const CameraView& view, int width,
                                            int height) {
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
