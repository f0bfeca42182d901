#pragma once
/// The HTML report: `revisit report RUN_DIR` calls WriteReport, `revisit inspect` calls WriteClosurePage or
/// WriteMapPairPage (issue 8). Pages open from disk: images and plots are files beside them, linked relatively.
#include "closures/density_image.hpp"
#include "render/density_pictures.hpp"
#include "render/scene_common.hpp"
#include "report/report_input.hpp"

#include <filesystem>

namespace revisit {

struct ReportConfig {
    RenderConfig overview;                 ///< overview pictures (1280 x 960)
    RenderConfig pair;                     ///< per-closure 3D views; MapPairRenderConfig() by default
    DensityPictureConfig density_pictures;
    DensityImageConfig density;            ///< when density images are computed from maps (no load_density_image)
    int thumbnail_width = 240;             ///< [px]
    bool closure_pages = true;             ///< one page per closure (index thumbnails link to them)
    bool map_pages = true;                 ///< one page per local map in ReportInput::map_ids
    ReportConfig();
};

struct ReportStats {
    int pages = 0;
    int images = 0;  ///< PNG and SVG files written
};

/// Writes report_dir/index.html with its images, plots, one page per closure and one per local map. Creates
/// the folder.
ReportStats WriteReport(const ReportInput& input, const std::filesystem::path& report_dir, const ReportConfig& config = {});

/// Writes the page of input.closures[closure_index] (report_dir/closure_NNNN.html) and its pictures; returns its path.
std::filesystem::path WriteClosurePage(const ReportInput& input, std::size_t closure_index,
                                       const std::filesystem::path& report_dir, const ReportConfig& config = {});

/// The same comparison for any two local maps, detected or not (`revisit inspect --maps A B`): density images,
/// overlay and 3D view at the odometry relative pose, so a user can see why a closure was missed.
std::filesystem::path WriteMapPairPage(const ReportInput& input, int query_map_id, int ref_map_id,
                                       const std::filesystem::path& report_dir, const ReportConfig& config = {});

}  // namespace revisit
