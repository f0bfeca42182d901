#include "exports/occupancy_grid.hpp"

#include <opencv2/imgcodecs.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <iomanip>
#include <limits>

#include "core/error.hpp"

namespace revisit {
namespace {

/// Counts saturate: a cell seen that often keeps its share.
void Count(std::uint16_t& count) {
    if (count < std::numeric_limits<std::uint16_t>::max()) ++count;
}

}  // namespace

OccupancyGrid::OccupancyGrid(const Eigen::AlignedBox2d& extent, double resolution) : resolution_(resolution) {
    if (!(resolution > 0.0)) throw ConfigError("occupancy.resolution must be positive");
    origin_ = extent.isEmpty() ? Eigen::Vector2d::Zero() : extent.min();
    const Eigen::Vector2d size = extent.isEmpty() ? Eigen::Vector2d::Zero() : Eigen::Vector2d(extent.sizes());
    width_ = std::max(1, static_cast<int>(std::ceil(size.x() / resolution)) + 1);
    height_ = std::max(1, static_cast<int>(std::ceil(size.y() / resolution)) + 1);
    hits_.assign(std::size_t(width_) * std::size_t(height_), 0);
    misses_.assign(hits_.size(), 0);
}

bool OccupancyGrid::Cell(const Eigen::Vector2d& point, int& x, int& y) const {
    const double fx = std::floor((point.x() - origin_.x()) / resolution_);
    const double fy = std::floor((point.y() - origin_.y()) / resolution_);
    if (!(fx >= 0 && fy >= 0 && fx < width_ && fy < height_)) return false;  // NaN fails too
    x = static_cast<int>(fx);
    y = static_cast<int>(fy);
    return true;
}

void OccupancyGrid::AddHit(const Eigen::Vector2d& point) {
    int x = 0, y = 0;
    if (Cell(point, x, y)) Count(hits_[Index(x, y)]);
}

void OccupancyGrid::AddMiss(const Eigen::Vector2d& point) {
    int x = 0, y = 0;
    if (Cell(point, x, y)) Count(misses_[Index(x, y)]);
}

void OccupancyGrid::AddRay(const Eigen::Vector2d& from, const Eigen::Vector2d& to) {
    if (!from.allFinite() || !to.allFinite()) return;
    // Bresenham between the two cells, in cell coordinates (rays may start or end outside the grid).
    const Eigen::Vector2d a = (from - origin_) / resolution_;
    const Eigen::Vector2d b = (to - origin_) / resolution_;
    const double limit = 4.0 * double(std::max(width_, height_));
    if (a.cwiseAbs().maxCoeff() > limit || b.cwiseAbs().maxCoeff() > limit) return;
    long x = static_cast<long>(std::floor(a.x())), y = static_cast<long>(std::floor(a.y()));
    const long x1 = static_cast<long>(std::floor(b.x())), y1 = static_cast<long>(std::floor(b.y()));
    const long dx = std::labs(x1 - x), dy = -std::labs(y1 - y);
    const long sx = x < x1 ? 1 : -1, sy = y < y1 ? 1 : -1;
    long error = dx + dy;
    while (x != x1 || y != y1) {
        if (x >= 0 && y >= 0 && x < width_ && y < height_) Count(misses_[Index(int(x), int(y))]);
        const long twice = 2 * error;
        if (twice >= dy) {
            error += dy;
            x += sx;
        }
        if (twice <= dx) {
            error += dx;
            y += sy;
        }
    }
    AddHit(to);
}

std::uint8_t OccupancyGrid::Classify(int x, int y, double occupied_share) const {
    const double h = hits_[Index(x, y)], m = misses_[Index(x, y)];
    if (h + m == 0) return kPgmUnknown;
    return h > 0 && h >= occupied_share * (h + m) ? kPgmOccupied : kPgmFree;
}

std::vector<std::uint8_t> OccupancyGrid::Image(double occupied_share) const {
    std::vector<std::uint8_t> pixels(hits_.size());
    for (int y = 0; y < height_; ++y) {
        const std::size_t row = std::size_t(height_ - 1 - y) * std::size_t(width_);
        for (int x = 0; x < width_; ++x) pixels[row + std::size_t(x)] = Classify(x, y, occupied_share);
    }
    return pixels;
}

double FittingResolution(const Eigen::AlignedBox2d& extent, double resolution, int max_cells) {
    if (extent.isEmpty() || max_cells < 1) return resolution;
    const double side = extent.sizes().maxCoeff();
    while (side / resolution + 1.0 > double(max_cells)) resolution *= 2.0;
    return resolution;
}

void WritePgm(std::ostream& out, const OccupancyGrid& grid, double occupied_share) {
    const auto pixels = grid.Image(occupied_share);
    out << "P5\n" << grid.width() << ' ' << grid.height() << "\n255\n";
    out.write(reinterpret_cast<const char*>(pixels.data()), static_cast<std::streamsize>(pixels.size()));
}

void WritePng(std::ostream& out, const OccupancyGrid& grid, double occupied_share) {
    auto pixels = grid.Image(occupied_share);
    const cv::Mat image(grid.height(), grid.width(), CV_8UC1, pixels.data());
    std::vector<std::uint8_t> bytes;
    if (!cv::imencode(".png", image, bytes, {cv::IMWRITE_PNG_COMPRESSION, 9})) throw std::runtime_error("PNG encoding of the occupancy grid failed");
    out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
}

void WriteMapYaml(std::ostream& out, const OccupancyGrid& grid, const std::string& image_name) {
    // Loaders compute occ = (255 - pixel) / 255 and call a cell occupied above occupied_thresh, free
    // below free_thresh: 0 -> 1.0 occupied, 254 -> 0.004 free, 205 -> 0.196 (just above 0.196) unknown.
    // A name of plain characters stays plain, as map_saver writes it; any other is a quoted YAML string.
    const bool plain = !image_name.empty() && std::all_of(image_name.begin(), image_name.end(), [](unsigned char c) {
        return std::isalnum(c) || c == '.' || c == '_' || c == '-' || c == '/';
    });
    std::string quoted = "\"";
    for (const char c : image_name) {
        if (c == '"' || c == '\\') quoted += '\\';
        quoted += c;
    }
    quoted += '"';
    out << std::setprecision(9);
    out << "image: " << (plain ? image_name : quoted) << '\n'
        << "mode: trinary\n"
        << "resolution: " << grid.resolution() << '\n'
        << "origin: [" << grid.origin().x() << ", " << grid.origin().y() << ", 0.0]\n"
        << "negate: 0\n"
        << "occupied_thresh: 0.65\n"
        << "free_thresh: 0.196\n";
}

}  // namespace revisit
