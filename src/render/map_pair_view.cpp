#include "render/map_pair_view.hpp"

#include <cstdio>

namespace revisit {

RenderConfig MapPairRenderConfig() {
    RenderConfig config;
    // Before and after side by side on the page (1,352 px of content): each under half its width.
    config.width = 640;
    config.height = 480;
    config.point_size = 1.0;  // dense local maps: small points keep both colours visible where maps overlap
    config.oblique_elevation_deg = 45.0;
    config.margin = 0.02;
    return config;
}

cv::Mat RenderMapPair(const std::vector<Eigen::Vector3f>& query_points, const std::vector<Eigen::Vector3f>& ref_points,
                      const Eigen::Isometry3d& T_query_ref, const std::string& title, bool oblique,
                      const RenderConfig& config) {
    // Frame the pair on the query map: that is where the overlap has to be judged.
    Extent extent;
    const std::size_t stride = std::max<std::size_t>(1, query_points.size() / 50000);
    for (std::size_t i = 0; i < query_points.size(); i += stride) extent.Add(query_points[i].cast<double>());
    if (extent.Empty())
        for (std::size_t i = 0; i < ref_points.size(); i += std::max<std::size_t>(1, ref_points.size() / 50000))
            extent.Add(T_query_ref * ref_points[i].cast<double>());

    double grid_spacing = 0.0;
    const auto build = [&](mrpt::opengl::COpenGLScene& scene) {
        scene.getViewport()->setCustomBackgroundColor({1.f, 1.f, 1.f});
        grid_spacing = oblique ? AddGroundGrid(scene, extent, GroundHeight(query_points, extent)) : 0.0;
        AddUniformCloud(scene, ref_points, T_query_ref, palette::kRefMap, config);
        AddUniformCloud(scene, query_points, Eigen::Isometry3d::Identity(), palette::kQueryMap, config);
    };
    RenderedFrame frame = OffscreenRenderer::Instance().Render(build, FrameExtent(extent, oblique, config), config.width,
                                                               config.height);
    std::vector<LegendEntry> legend{{"query map", palette::kQueryMap, false}, {"reference map", palette::kRefMap, false}};
    if (grid_spacing > 0.0) {
        char text[48];
        std::snprintf(text, sizeof(text), "grid %g m", grid_spacing);
        legend.push_back({text, {215, 215, 215}});
    }
    DrawLegend(frame.image, legend, title);
    if (!extent.Empty()) AnnotateOrientation(frame, 0.5 * (extent.min + extent.max), oblique);
    return frame.image;
}

}  // namespace revisit
