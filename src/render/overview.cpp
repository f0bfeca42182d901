#include "render/overview.hpp"

#include <opencv2/imgproc.hpp>

#include <cstdio>

namespace revisit {
namespace {

Extent ContentExtent(const OverviewData& data) {
    Extent extent;
    for (const auto* trajectory : {&data.odometry, &data.corrected, &data.reference})
        for (const auto& p : *trajectory) extent.Add(p);
    // The map decides the extent too, but through a subsample: stray far points must not shrink the picture.
    const std::size_t stride = std::max<std::size_t>(1, data.map_points.size() / 50000);
    for (std::size_t i = 0; i < data.map_points.size(); i += stride) extent.Add(data.map_points[i].cast<double>());
    return extent;
}

}  // namespace

cv::Mat RenderOverview(const OverviewData& data, OverviewView view, const RenderConfig& config) {
    const bool oblique = view == OverviewView::kOblique;
    const Extent extent = ContentExtent(data);
    double grid_spacing = 0.0;
    const auto build = [&](mrpt::opengl::COpenGLScene& scene) {
        scene.getViewport()->setCustomBackgroundColor({1.f, 1.f, 1.f});
        grid_spacing = oblique ? AddGroundGrid(scene, extent, GroundHeight(data.map_points, extent)) : 0.0;
        AddHeightColoredCloud(scene, data.map_points, config);
    };
    RenderedFrame frame = OffscreenRenderer::Instance().Render(build, FrameExtent(extent, oblique, config), config.width,
                                                               config.height);

    const int thick = config.line_thickness;
    // Under everything: the reference as a wide light band, so the corrected line shows on it where they agree.
    DrawPolylines(frame.image, {ProjectPolyline(frame, data.reference)}, palette::kReferenceBand, 3 * thick + 4);
    DrawPolylines(frame.image, {ProjectPolyline(frame, data.corrected)}, palette::kCorrected, thick);
    // The odometry dashed on top: "before" stays visible where it runs along the corrected line.
    DrawDashedPolyline(frame.image, ProjectPolyline(frame, data.odometry), palette::kOdometry, thick, 14.0, 9.0);
    std::size_t accepted = 0, rejected = 0;
    for (const auto& closure : data.closures) {
        const Polyline2d at = ProjectPolyline(frame, {closure.position});
        if (at.empty()) continue;
        if (closure.accepted) {
            cv::circle(frame.image, at.front(), thick + 4, palette::kBackground.Bgr(), cv::FILLED, cv::LINE_AA);
            cv::circle(frame.image, at.front(), thick + 2, palette::kAccepted.Bgr(), cv::FILLED, cv::LINE_AA);
            ++accepted;
        } else {
            cv::circle(frame.image, at.front(), thick + 2, palette::kRejected.Bgr(), 2, cv::LINE_AA);
            ++rejected;
        }
    }

    std::vector<LegendEntry> legend;
    if (!data.map_points.empty()) {
        legend.push_back({"map, low", HeightColor(0.0), false});
        legend.push_back({"map, high", HeightColor(1.0), false});
    }
    if (!data.odometry.empty()) legend.push_back({"odometry (dashed)", palette::kOdometry});
    if (!data.corrected.empty()) legend.push_back({"corrected", palette::kCorrected});
    if (!data.reference.empty()) legend.push_back({"reference (band)", palette::kReferenceBand});
    if (accepted > 0) legend.push_back({"accepted closure (" + std::to_string(accepted) + ")", palette::kAccepted, false});
    if (rejected > 0) legend.push_back({"rejected closure (" + std::to_string(rejected) + ")", palette::kRejected, false});
    if (oblique && grid_spacing > 0.0) {
        char text[48];
        std::snprintf(text, sizeof(text), "grid %g m", grid_spacing);
        legend.push_back({text, {215, 215, 215}});
    }
    DrawLegend(frame.image, legend, oblique ? "Overview (oblique)" : "Overview (top-down)");
    if (!extent.Empty()) AnnotateOrientation(frame, 0.5 * (extent.min + extent.max), oblique);
    return frame.image;
}

}  // namespace revisit
