#pragma once
/// One page comparing two local maps (a detected closure, or any pair asked for by `revisit inspect --maps`).
#include "report/report_writer.hpp"

#include <filesystem>
#include <opencv2/core.hpp>
#include <string>

namespace revisit {

struct PairPage {
    std::filesystem::path page;   ///< the written .html
    std::string thumbnail;        ///< file name of the thumbnail beside it, empty when no picture could be drawn
    int images = 0;
};

/// Writes `<stem>.html` and `<stem>_*.png` into report_dir. `detected` tells whether `entry` is a real closure
/// (matches, estimated pose) or an ad-hoc pair shown at its odometry pose. `nav_html` is put at the top.
PairPage WritePairPage(const ReportInput& input, const ClosureEntry& entry, bool detected, const std::string& stem,
                       const std::filesystem::path& report_dir, const ReportConfig& config, const std::string& nav_html);

/// Writes a PNG (throws std::runtime_error when it cannot).
void WritePng(const std::filesystem::path& path, const cv::Mat& image);

/// Writes a text file (throws std::runtime_error when it cannot).
void WriteText(const std::filesystem::path& path, const std::string& text);

}  // namespace revisit
