#include "report/map_page.hpp"

#include "render/density_pictures.hpp"
#include "report/html_page.hpp"
#include "report/index_tables.hpp"
#include "report/svg_plot.hpp"

#include <optional>
#include <vector>

namespace revisit {
namespace {

/// The candidates `map_id` takes part in, as an HTML list linking to their pages (or naming the command that
/// renders them) and to the other map's page.
std::string ClosureList(const ReportInput& input, int map_id, const ReportPlan& plan) {
    std::string html;
    for (std::size_t i = 0; i < input.closures.size(); ++i) {
        const auto& entry = input.closures[i];
        const Closure& c = entry.closure;
        if (c.query_id != map_id && c.ref_id != map_id) continue;
        const bool as_query = c.query_id == map_id;
        const int other = as_query ? c.ref_id : c.query_id;
        html += "<li>" + ClosureRef(plan, i) + ": " + EscapeXml(as_query ? "query, reference " : "reference of ") +
                MapRef(plan, other) +
                EscapeXml(", " + ClosureEvidence(entry) + ", " + ClosureStatus(entry)) +
                "</li>\n";
    }
    return html.empty() ? "<p>No closure candidate involves this map.</p>\n" : "<ul>\n" + html + "</ul>\n";
}

}  // namespace

WrittenPage WriteMapPage(const ReportInput& input, int map_id, const std::filesystem::path& report_dir,
                         const ReportConfig& config, const ReportPlan& plan, const std::string& nav_html) {
    const std::string stem = MapStem(map_id);
    const auto map = LoadMap(input, map_id);
    const auto density = LoadDensity(input, map, map_id, config);
    const auto keypoints = input.load_keypoints ? input.load_keypoints(map_id) : std::vector<Eigen::Vector2f>{};

    HtmlPage page("Local map " + std::to_string(map_id));
    page.Raw(nav_html);
    std::vector<std::pair<std::string, std::string>> numbers;
    if (map) {
        const Eigen::Vector3d origin = map->T_world_map.translation();
        numbers.push_back({"scans", std::to_string(map->first_scan) + "-" + std::to_string(map->last_scan)});
        numbers.push_back({"points (as stored)", std::to_string(map->points.size())});
        numbers.push_back({"origin (odometry, world)", "x " + FormatNumber(origin.x()) + " m, y " + FormatNumber(origin.y()) +
                                                           " m, z " + FormatNumber(origin.z()) + " m"});
    }
    if (density) {
        numbers.push_back({"density image", std::to_string(density->image.cols) + " x " + std::to_string(density->image.rows) +
                                                " px at " + FormatNumber(density->resolution) + " m/px"});
    }
    if (input.load_keypoints) numbers.push_back({"ORB keypoints", std::to_string(keypoints.size())});
    page.KeyValueTable(numbers);

    WrittenPage result;
    if (density) {
        const std::string title = "map " + std::to_string(map_id) +
                                  (map ? " (scans " + std::to_string(map->first_scan) + "-" + std::to_string(map->last_scan) + ")" : "");
        const cv::Mat picture = DrawDensityKeypoints(*density, keypoints, title, config.density_pictures);
        WritePng(report_dir / (stem + "_density.png"), picture);
        page.Figure(stem + "_density.png", "density image and ORB keypoints");
        result.thumbnail = WriteThumbnail(picture, stem, report_dir, config.thumbnail_width);
        result.images += 2;
    } else {
        page.Paragraph("No map data available in this run: the density image cannot be drawn.");
    }
    page.Heading("Closure candidates", 2);
    page.Raw(ClosureList(input, map_id, plan));
    result.page = report_dir / (stem + ".html");
    WriteText(result.page, page.Finish());
    return result;
}

}  // namespace revisit
