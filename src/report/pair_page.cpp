#include "report/pair_page.hpp"

#include "core/atomic_file.hpp"
#include "render/map_pair_view.hpp"
#include "render/png_encoding.hpp"
#include "report/html_page.hpp"
#include "report/index_tables.hpp"

#include <opencv2/imgproc.hpp>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <stdexcept>

namespace revisit {

std::optional<LocalMap> LoadMap(const ReportInput& input, int id) {
    return input.load_local_map ? input.load_local_map(id) : std::nullopt;
}

std::optional<DensityImage> LoadDensity(const ReportInput& input, const std::optional<LocalMap>& map, int id,
                                        const ReportConfig& config) {
    if (input.load_density_image)
        if (auto image = input.load_density_image(id)) return image;
    // Not stored in the run: recompute from the map (unlevelled; fine for looking at it).
    if (map) return ComputeDensityImage(map->points, config.density);
    return std::nullopt;
}

namespace {

/// Relative pose of two maps from the odometry: what the detector had before any closure.
std::optional<Eigen::Matrix4d> OdometryRelativePose(const ReportInput& input, const ClosureEntry& entry,
                                                   const std::optional<LocalMap>& query, const std::optional<LocalMap>& ref) {
    if (query && ref) return (query->T_world_map.inverse() * ref->T_world_map).matrix();
    const auto& poses = input.odometry.T_world_sensor;
    const auto q = entry.closure.query_scans.first, r = entry.closure.ref_scans.first;
    if (q < poses.size() && r < poses.size()) return (poses[q].inverse() * poses[r]).matrix();
    return std::nullopt;
}

std::string PoseText(const Eigen::Matrix4d& T) {
    const double yaw = std::atan2(T(1, 0), T(0, 0)) * 180.0 / M_PI;
    return "x " + FormatNumber(T(0, 3)) + " m, y " + FormatNumber(T(1, 3)) + " m, z " + FormatNumber(T(2, 3)) +
           " m, yaw " + FormatNumber(yaw, 2) + " deg";
}

std::string Optional(const std::optional<double>& value, const std::string& unit, int decimals = 3) {
    return value ? FormatNumber(*value, decimals) + unit : "-";
}

/// What the alignment changed against the odometry, in words and numbers; says so when the two overlays must look
/// alike (the change is below two density-image cells and a degree).
std::string AlignmentSentence(const Eigen::Matrix4d& T_odometry, const Eigen::Matrix4d& T_after, double cell_m,
                              const OverlayAgreement& at_odometry, const OverlayAgreement& after) {
    const Eigen::Matrix4d delta = T_odometry.inverse() * T_after;
    const double moved_m = std::hypot(delta(0, 3), delta(1, 3));
    const double turned_deg = std::abs(std::atan2(delta(1, 0), delta(0, 0))) * 180.0 / M_PI;
    std::string text = "The alignment moves the reference map " + FormatNumber(moved_m, 2) + " m and " +
                       FormatNumber(turned_deg, 2) + " deg from the odometry pose. ";
    if (moved_m < 2.0 * cell_m && turned_deg < 1.0)
        text += "That is less than two density-image cells (" + FormatNumber(2.0 * cell_m, 2) +
                " m): the odometry already laid the maps over each other, so the two overlays look alike. ";
    const auto percent = [](const OverlayAgreement& a) { return FormatNumber(100.0 * a.Fraction(), 0) + "%"; };
    text += "Occupied query cells with reference structure in the same cell: " + percent(at_odometry) +
            " at the odometry pose, " + percent(after) + " after alignment.";
    return text;
}

}  // namespace

std::string ClosureStem(std::size_t index) {
    char stem[32];
    std::snprintf(stem, sizeof(stem), "closure_%04zu", index);
    return stem;
}

std::string MapStem(int map_id) {
    char stem[32];
    std::snprintf(stem, sizeof(stem), "map_%04d", map_id);
    return stem;
}

void WritePng(const std::filesystem::path& path, const cv::Mat& image) {
    // Encoded in memory, then written all or nothing like every other file (core/atomic_file.hpp).
    std::vector<std::uint8_t> png;
    try {
        png = EncodePng(image);
    } catch (const std::exception& e) {
        throw std::runtime_error("report: cannot encode " + path.string() + ": " + e.what());
    }
    WriteFileAtomically(path, std::string_view(reinterpret_cast<const char*>(png.data()), png.size()));
}

std::string WriteThumbnail(const cv::Mat& image, const std::string& stem, const std::filesystem::path& dir, int width) {
    cv::Mat thumb;
    const double scale = double(width) / image.cols;
    cv::resize(image, thumb, cv::Size(), scale, scale, cv::INTER_AREA);
    const std::string name = stem + "_thumb.png";
    WritePng(dir / name, thumb);
    return name;
}

void WriteText(const std::filesystem::path& path, const std::string& text) {
    WriteFileAtomically(path, text);
}

WrittenPage WritePairPage(const ReportInput& input, const ClosureEntry& entry, bool detected, const std::string& stem,
                       const std::filesystem::path& report_dir, const ReportConfig& config, const std::string& nav_html) {
    Closure c = entry.closure;
    // Closure files keep only the matches; both maps' keypoints come from the run's database.
    if (input.load_keypoints) {
        if (c.query_keypoints.empty()) c.query_keypoints = input.load_keypoints(c.query_id);
        if (c.ref_keypoints.empty()) c.ref_keypoints = input.load_keypoints(c.ref_id);
    }
    const auto query_map = LoadMap(input, c.query_id);
    const auto ref_map = LoadMap(input, c.ref_id);
    const auto query_density = LoadDensity(input, query_map, c.query_id, config);
    const auto ref_density = LoadDensity(input, ref_map, c.ref_id, config);
    const auto T_odometry = OdometryRelativePose(input, entry, query_map, ref_map);
    const Eigen::Matrix4d T_after = entry.T_query_ref_refined.value_or(c.T_query_ref);

    WrittenPage result;
    HtmlPage page(detected ? "Closure: map " + std::to_string(c.query_id) + " to map " + std::to_string(c.ref_id)
                           : "Maps " + std::to_string(c.query_id) + " and " + std::to_string(c.ref_id) + " (not a detected closure)");
    page.Raw(nav_html);
    std::vector<std::pair<std::string, std::string>> numbers{
        {"query map", std::to_string(c.query_id) + " (session " + std::to_string(c.query_session) + ", scans " +
                          std::to_string(c.query_scans.first) + "-" + std::to_string(c.query_scans.last) + ")"},
        {"reference map", std::to_string(c.ref_id) + " (session " + std::to_string(c.ref_session) + ", scans " +
                              std::to_string(c.ref_scans.first) + "-" + std::to_string(c.ref_scans.last) + ")"}};
    if (detected) {
        numbers.push_back({"source", entry.proximity ? "proximity pass: registered because the corrected poses laid the maps "
                                                       "over each other (no image matching)"
                                                     : "density-image detector"});
        numbers.push_back({"status", ClosureStatus(entry) + (entry.reason.empty() ? "" : " (" + entry.reason + ")")});
        if (!entry.proximity) {
            numbers.push_back({"matches / inliers / votes", std::to_string(c.matches.size()) + " / " +
                                                                std::to_string(c.num_inliers) + " / " + std::to_string(c.num_votes)});
            numbers.push_back({"T_query_ref (detector)", PoseText(c.T_query_ref)});
        }
        if (entry.T_query_ref_refined) numbers.push_back({"T_query_ref (registered in 3D)", PoseText(*entry.T_query_ref_refined)});
        numbers.push_back({"registration overlap", Optional(entry.fitness, "")});
        numbers.push_back({"registration RMS", Optional(entry.rmse, " m")});
        numbers.push_back({"ground-truth error (planar, yaw)", Optional(entry.gt_translation_error, " m") + ", " +
                                                                   Optional(entry.gt_rotation_error, " deg", 2)});
        if (entry.gt_true_positive) numbers.push_back({"ground truth", *entry.gt_true_positive ? "true closure" : "false closure"});
    }
    if (T_odometry) numbers.push_back({"T_query_ref (odometry)", PoseText(*T_odometry)});
    page.KeyValueTable(numbers);

    const auto emit = [&](const std::string& suffix, const cv::Mat& image, const std::string& caption) {
        const std::string name = stem + suffix + ".png";
        WritePng(report_dir / name, image);
        ++result.images;
        page.Figure(name, caption);
        if (result.thumbnail.empty()) {
            result.thumbnail = WriteThumbnail(image, stem, report_dir, config.thumbnail_width);
            ++result.images;
        }
    };
    if (query_density && ref_density) {
        page.Heading("Density images", 2);
        // The proximity pass matched no images: a matches picture would show nothing it used.
        if (!detected || !entry.proximity)
            emit("_matches", DrawDensityMatches(*query_density, *ref_density, c, config.density_pictures),
                 detected ? "ORB keypoints and matches: inliers green, outliers faint red" : "density images and keypoints");
        OverlayAgreement at_odometry, after;
        if (T_odometry)
            emit("_overlay_odometry",
                 DrawDensityOverlay(*query_density, *ref_density, *T_odometry, "at the odometry pose (before)",
                                    config.density_pictures, &at_odometry),
                 "overlay at the odometry pose (before)");
        if (detected)
            emit("_overlay", DrawDensityOverlay(*query_density, *ref_density, T_after, "after alignment", config.density_pictures, &after),
                 "overlay after alignment");
        if (detected && T_odometry)
            page.Paragraph(AlignmentSentence(*T_odometry, T_after, query_density->resolution, at_odometry, after));
    }
    if (query_map && ref_map) {
        page.Heading("Local maps in 3D", 2);
        if (T_odometry)
            emit("_3d_before", RenderMapPair(query_map->points, ref_map->points, Eigen::Isometry3d(*T_odometry), "before (odometry)",
                                             true, config.pair),
                 "before alignment: odometry relative pose");
        if (detected)
            emit("_3d_after", RenderMapPair(query_map->points, ref_map->points, Eigen::Isometry3d(T_after), "after alignment",
                                            true, config.pair),
                 "after alignment");
    }
    if (result.images == 0) page.Paragraph("No map data available in this run: pictures cannot be drawn.");
    result.page = report_dir / (stem + ".html");
    WriteText(result.page, page.Finish());
    return result;
}

}  // namespace revisit
