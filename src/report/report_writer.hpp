#pragma once
/// The HTML report: `revisit report RUN_DIR` calls WriteReport, `revisit inspect` calls WriteClosurePage or
/// WriteMapPairPage (issue 8). Pages open from disk: images and plots are files beside them, linked relatively.
#include "closures/density_image.hpp"
#include "render/density_pictures.hpp"
#include "render/scene_common.hpp"
#include "report/report_input.hpp"
#include "report/report_plan.hpp"

#include <filesystem>
#include <functional>

namespace revisit {

struct ReportConfig {
    RenderConfig overview;                 ///< overview pictures (ReportConfig(): 1000 x 750, shown at that size)
    RenderConfig pair;                     ///< per-closure 3D views; MapPairRenderConfig() by default
    DensityPictureConfig density_pictures;
    DensityImageConfig density;            ///< when density images are computed from maps (no load_density_image)
    int thumbnail_width = 240;             ///< [px] the one thumbnail size (closures and maps)
    /// Which closures and maps get a page (report_plan.hpp); the others are table rows, rendered on
    /// demand by `revisit inspect`.
    ReportPagePlan pages;
    ReportConfig();
};

struct ReportStats {
    int pages = 0;
    int images = 0;  ///< PNG and SVG files written
};

/// Called with (0, total) before the first page and after each page is written, with the pages done and the
/// total (the index counts as the last page); calls are serialized, from any thread.
using ReportProgress = std::function<void(std::size_t pages_done, std::size_t pages_total)>;

/// Writes report_dir/index.html with its images and plots, and the pages PlanReport chooses (report_plan.hpp).
/// Creates the folder. Pages render in parallel (TBB); the files are the same at any thread count.
ReportStats WriteReport(const ReportInput& input, const std::filesystem::path& report_dir, const ReportConfig& config = {},
                        const ReportProgress& progress = {});

/// Writes the page of input.closures[closure_index] (report_dir/closure_NNNN.html) and its pictures; returns its path.
std::filesystem::path WriteClosurePage(const ReportInput& input, std::size_t closure_index,
                                       const std::filesystem::path& report_dir, const ReportConfig& config = {});

/// Writes the page of one local map (report_dir/map_NNNN.html) and its pictures; returns its path (`revisit inspect --map`).
std::filesystem::path WriteSingleMapPage(const ReportInput& input, int map_id, const std::filesystem::path& report_dir,
                                         const ReportConfig& config = {});

/// The same comparison for any two local maps, detected or not (`revisit inspect --maps A B`): density images,
/// overlay and 3D view at the odometry relative pose, so a user can see why a closure was missed.
std::filesystem::path WriteMapPairPage(const ReportInput& input, int query_map_id, int ref_map_id,
                                       const std::filesystem::path& report_dir, const ReportConfig& config = {});

}  // namespace revisit
