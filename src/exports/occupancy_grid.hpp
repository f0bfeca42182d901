#pragma once
/// An occupancy grid in the convention of ROS map_server / nav2 (a PGM image and its YAML): cells
/// count the rays that end in them (hits) and the rays that pass through them (misses).
#include <cstdint>
#include <ostream>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace revisit {

/// Pixel values of map_server's trinary images (what its map_saver writes).
constexpr std::uint8_t kPgmOccupied = 0;
constexpr std::uint8_t kPgmFree = 254;
constexpr std::uint8_t kPgmUnknown = 205;

class OccupancyGrid {
  public:
    /// Cells of `resolution` covering `extent` [m] (x right, y up); the grid's origin is extent.min().
    OccupancyGrid(const Eigen::AlignedBox2d& extent, double resolution);

    /// A ray from the sensor at `from` that returned at `to`: a miss in every cell it crosses (Bresenham),
    /// a hit in the cell it ends in. Parts outside the grid are skipped.
    void AddRay(const Eigen::Vector2d& from, const Eigen::Vector2d& to);
    void AddHit(const Eigen::Vector2d& point);
    void AddMiss(const Eigen::Vector2d& point);

    int width() const { return width_; }
    int height() const { return height_; }
    double resolution() const { return resolution_; }
    /// [m] the lower-left corner of cell (0, 0): map_server's `origin`.
    const Eigen::Vector2d& origin() const { return origin_; }
    std::uint32_t hits(int x, int y) const { return hits_[Index(x, y)]; }
    std::uint32_t misses(int x, int y) const { return misses_[Index(x, y)]; }

    /// kPgmOccupied, kPgmFree or kPgmUnknown (never observed).
    std::uint8_t Classify(int x, int y, double occupied_share) const;
    /// The image, row 0 at the top (largest y), as a PGM shows it.
    std::vector<std::uint8_t> Image(double occupied_share) const;

  private:
    std::size_t Index(int x, int y) const { return std::size_t(y) * std::size_t(width_) + std::size_t(x); }
    bool Cell(const Eigen::Vector2d& point, int& x, int& y) const;
    double resolution_;
    Eigen::Vector2d origin_;
    int width_ = 0;
    int height_ = 0;
    // Counts saturate at 65535: a cell seen that often keeps its share.
    std::vector<std::uint16_t> hits_;
    std::vector<std::uint16_t> misses_;
};

/// The resolution to use for `extent`: `resolution`, doubled until no side needs more than `max_cells` cells.
double FittingResolution(const Eigen::AlignedBox2d& extent, double resolution, int max_cells);

/// Binary PGM (P5, 8 bit).
void WritePgm(std::ostream& out, const OccupancyGrid& grid, double occupied_share);
/// The same pixels as an 8-bit grey PNG (zlib level 9): map_server and nav2 read it alike, and a drive's
/// grid, mostly unknown cells, takes a fraction of the PGM's bytes (11 MB -> under 1 MB on a highway).
void WritePng(std::ostream& out, const OccupancyGrid& grid, double occupied_share);
/// map_server's YAML: image (relative to the YAML), resolution, origin, negate, occupied_thresh and
/// free_thresh that read the PGM's three values back as occupied, free and unknown.
void WriteMapYaml(std::ostream& out, const OccupancyGrid& grid, const std::string& image_name);

}  // namespace revisit
