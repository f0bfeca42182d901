#pragma once
/// One page comparing two local maps (a detected closure, or any pair asked for by `revisit inspect --maps`).
#include "report/report_writer.hpp"

#include <filesystem>
#include <optional>
#include <opencv2/core.hpp>
#include <string>

namespace revisit {

/// A written page of the report.
struct WrittenPage {
    std::filesystem::path page;   ///< the written .html
    std::string thumbnail;        ///< file name of the thumbnail beside it, empty when no picture could be drawn
    int images = 0;
};

/// Writes `<stem>.html` and `<stem>_*.png` into report_dir. `detected` tells whether `entry` is a real closure
/// (matches, estimated pose) or an ad-hoc pair shown at its odometry pose. `nav_html` is put at the top.
WrittenPage WritePairPage(const ReportInput& input, const ClosureEntry& entry, bool detected, const std::string& stem,
                       const std::filesystem::path& report_dir, const ReportConfig& config, const std::string& nav_html);

/// A local map of the run, when the run has it.
std::optional<LocalMap> LoadMap(const ReportInput& input, int id);
/// A map's stored density image, else one computed from `map`, else nothing.
std::optional<DensityImage> LoadDensity(const ReportInput& input, const std::optional<LocalMap>& map, int id,
                                        const ReportConfig& config);

/// File stems of the per-closure and per-map pages: closure_NNNN, map_NNNN.
std::string ClosureStem(std::size_t index);
std::string MapStem(int map_id);

/// Writes a PNG (throws std::runtime_error when it cannot).
void WritePng(const std::filesystem::path& path, const cv::Mat& image);

/// Writes `<stem>_thumb.png`, `image` scaled to `width` pixels wide, into `dir`; returns its file name.
std::string WriteThumbnail(const cv::Mat& image, const std::string& stem, const std::filesystem::path& dir, int width);

/// Writes a text file (throws std::runtime_error when it cannot).
void WriteText(const std::filesystem::path& path, const std::string& text);

}  // namespace revisit
