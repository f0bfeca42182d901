#include "render/scene_common.hpp"

#include <mrpt/opengl/CGridPlaneXY.h>
#include <mrpt/opengl/CPointCloudColoured.h>

#include <algorithm>
#include <cmath>

namespace revisit {
namespace {

std::size_t Stride(std::size_t size, const RenderConfig& config) {
    return config.max_points == 0 ? 1 : std::max<std::size_t>(1, (size + config.max_points - 1) / config.max_points);
}

}  // namespace

Eigen::Vector2d RobustHeightRange(const std::vector<Eigen::Vector3f>& points) {
    if (points.empty()) return {0.0, 1.0};
    // Percentiles of a deterministic subsample: exact enough for colouring and fast on millions of points.
    const std::size_t stride = std::max<std::size_t>(1, points.size() / 20000);
    std::vector<float> z;
    for (std::size_t i = 0; i < points.size(); i += stride) z.push_back(points[i].z());
    const auto at = [&z](double q) {
        auto nth = z.begin() + static_cast<std::ptrdiff_t>(q * static_cast<double>(z.size() - 1));
        std::nth_element(z.begin(), nth, z.end());
        return static_cast<double>(*nth);
    };
    const double low = at(0.02);
    const double high = at(0.98);
    return {low, high > low + 1e-6 ? high : low + 1.0};
}

void AddHeightColoredCloud(mrpt::opengl::COpenGLScene& scene, const std::vector<Eigen::Vector3f>& points_world,
                           const RenderConfig& config) {
    if (points_world.empty()) return;
    const Eigen::Vector2d range = RobustHeightRange(points_world);
    auto cloud = mrpt::opengl::CPointCloudColoured::Create();
    const std::size_t stride = Stride(points_world.size(), config);
    cloud->reserve(points_world.size() / stride + 1);
    for (std::size_t i = 0; i < points_world.size(); i += stride) {
        const auto& p = points_world[i];
        const Rgb c = HeightColor((p.z() - range.x()) / (range.y() - range.x()));
        cloud->push_back(p.x(), p.y(), p.z(), c.r / 255.f, c.g / 255.f, c.b / 255.f);
    }
    cloud->setPointSize(static_cast<float>(config.point_size));
    scene.insert(cloud);
}

void AddUniformCloud(mrpt::opengl::COpenGLScene& scene, const std::vector<Eigen::Vector3f>& points,
                     const Eigen::Isometry3d& T_world_points, Rgb color, const RenderConfig& config) {
    if (points.empty()) return;
    auto cloud = mrpt::opengl::CPointCloudColoured::Create();
    const std::size_t stride = Stride(points.size(), config);
    const Eigen::Isometry3f T = T_world_points.cast<float>();
    cloud->reserve(points.size() / stride + 1);
    for (std::size_t i = 0; i < points.size(); i += stride) {
        const Eigen::Vector3f p = T * points[i];
        cloud->push_back(p.x(), p.y(), p.z(), color.r / 255.f, color.g / 255.f, color.b / 255.f);
    }
    cloud->setPointSize(static_cast<float>(config.point_size));
    scene.insert(cloud);
}

CameraView FrameExtent(const Extent& extent, bool oblique, const RenderConfig& config) {
    CameraView view;
    if (extent.Empty()) return view;
    const Eigen::Vector3d size = (extent.max - extent.min).cwiseMax(Eigen::Vector3d::Constant(1.0));
    view.target = 0.5 * (extent.min + extent.max);
    const double aspect = static_cast<double>(config.width) / config.height;
    const double scale = 1.0 + 2.0 * config.margin;
    if (!oblique) {
        // MRPT's orthographic camera shows a height of distance / 2 (its projection uses +-distance / 4).
        view.target.z() = extent.max.z() + 1.0;
        view.distance = 2.0 * scale * std::max(size.y(), size.x() / aspect);
        view.orthographic = true;
        view.azimuth_deg = -90.0;
        view.elevation_deg = 90.0;
        return view;
    }
    view.orthographic = false;
    view.fov_deg = config.fov_deg;
    view.azimuth_deg = config.oblique_azimuth_deg;
    view.elevation_deg = config.oblique_elevation_deg;
    view.target.z() = extent.min.z();
    // Fit a sphere around the content: horizontally through the wider field of view, vertically through the
    // foreshortened ground (sin of the elevation); the larger of the two distances wins.
    const double radius = 0.5 * std::max(size.head<2>().norm(), size.z());
    const double tan_half_v = std::tan(0.5 * config.fov_deg * M_PI / 180.0);
    const double sin_elevation = std::sin(config.oblique_elevation_deg * M_PI / 180.0);
    view.distance = scale * radius * std::max(1.0 / (aspect * tan_half_v), std::max(sin_elevation, 0.3) / tan_half_v);
    return view;
}

double GroundHeight(const std::vector<Eigen::Vector3f>& points, const Extent& extent) {
    return points.empty() ? extent.min.z() : RobustHeightRange(points).x();
}

double AddGroundGrid(mrpt::opengl::COpenGLScene& scene, const Extent& extent, double z) {
    if (extent.Empty()) return 0.0;
    const Eigen::Vector3d size = extent.max - extent.min;
    const double spacing = NiceLength(std::max(size.x(), size.y()) / 10.0);
    const auto snap_down = [spacing](double v) { return std::floor(v / spacing) * spacing; };
    const auto snap_up = [spacing](double v) { return std::ceil(v / spacing) * spacing; };
    auto grid = mrpt::opengl::CGridPlaneXY::Create(
        static_cast<float>(snap_down(extent.min.x())), static_cast<float>(snap_up(extent.max.x())),
        static_cast<float>(snap_down(extent.min.y())), static_cast<float>(snap_up(extent.max.y())),
        static_cast<float>(z), static_cast<float>(spacing));
    grid->setColor_u8(mrpt::img::TColor(215, 215, 215));
    scene.insert(grid);
    return spacing;
}

Polyline2d ProjectPolyline(const RenderedFrame& frame, const std::vector<Eigen::Vector3d>& points_world) {
    Polyline2d pixels;
    pixels.reserve(points_world.size());
    cv::Point2d pixel;
    for (const auto& p : points_world)
        if (frame.Project(p, pixel)) pixels.push_back(pixel);
    return pixels;
}

void AnnotateOrientation(RenderedFrame& frame, const Eigen::Vector3d& centre_world, bool oblique) {
    cv::Point2d centre, east, north, up;
    if (!frame.Project(centre_world, centre) || !frame.Project(centre_world + Eigen::Vector3d::UnitX(), east) ||
        !frame.Project(centre_world + Eigen::Vector3d::UnitY(), north) ||
        !frame.Project(centre_world + Eigen::Vector3d::UnitZ(), up))
        return;
    if (!oblique) {
        DrawScaleBar(frame.image, std::hypot(east.x - centre.x, east.y - centre.y));
        const cv::Point2d d = north - centre;
        DrawNorthArrow(frame.image, std::atan2(d.x, -d.y));
        return;
    }
    DrawAxesGlyph(frame.image, east - centre, north - centre, up - centre);
}

}  // namespace revisit
