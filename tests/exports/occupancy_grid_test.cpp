/// The occupancy grid against readers that are not ours: OpenCV reads the PGM, yaml-cpp the YAML, and
/// a pixel is turned back into metres with map_server's rule (origin = the lower-left pixel's corner).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <opencv2/imgcodecs.hpp>
#include <yaml-cpp/yaml.h>

#include "exports/occupancy_grid.hpp"
#include "test_data.hpp"

namespace revisit {
namespace {
namespace fs = std::filesystem;

/// An empty 10 m x 6 m room with walls at x = 0, x = 10, y = 0, y = 6; the range along a ray from inside.
double RoomRange(const Eigen::Vector2d& from, double angle) {
    const Eigen::Vector2d d(std::cos(angle), std::sin(angle));
    double range = 1e9;
    if (d.x() > 1e-12) range = std::min(range, (10.0 - from.x()) / d.x());
    if (d.x() < -1e-12) range = std::min(range, (0.0 - from.x()) / d.x());
    if (d.y() > 1e-12) range = std::min(range, (6.0 - from.y()) / d.y());
    if (d.y() < -1e-12) range = std::min(range, (0.0 - from.y()) / d.y());
    return range;
}

/// The room scanned with 1,000 beams (dense enough that every cell inside is crossed) from a few places.
OccupancyGrid ScannedRoom(double resolution) {
    Eigen::AlignedBox2d extent(Eigen::Vector2d(-0.5, -0.5), Eigen::Vector2d(10.5, 6.5));
    OccupancyGrid grid(extent, resolution);
    for (double x = 2.0; x <= 8.0; x += 1.5) {
        const Eigen::Vector2d from(x, 3.0 + 0.2 * std::sin(x));
        for (int beam = 0; beam < 1000; ++beam) {
            const double angle = 2.0 * M_PI * beam / 1000.0;
            grid.AddRay(from, from + RoomRange(from, angle) * Eigen::Vector2d(std::cos(angle), std::sin(angle)));
        }
    }
    return grid;
}

struct ReadBack {
    cv::Mat image;
    double resolution = 0.0;
    Eigen::Vector2d origin = Eigen::Vector2d::Zero();
    /// map_server's rule: pixel (column, row) covers the cell whose lower-left corner is origin + (column, rows-1-row) x resolution.
    uchar At(const Eigen::Vector2d& point) const {
        const int column = static_cast<int>(std::floor((point.x() - origin.x()) / resolution));
        const int row = image.rows - 1 - static_cast<int>(std::floor((point.y() - origin.y()) / resolution));
        return image.at<uchar>(row, column);
    }
};

ReadBack WriteAndRead(const OccupancyGrid& grid, const fs::path& dir) {
    {
        std::ofstream pgm(dir / "room.pgm", std::ios::binary);
        WritePgm(pgm, grid, 0.25);
        std::ofstream yaml(dir / "room.yaml");
        WriteMapYaml(yaml, grid, "room.pgm");
    }
    ReadBack back;
    const YAML::Node yaml = YAML::LoadFile((dir / "room.yaml").string());
    EXPECT_EQ(yaml["image"].as<std::string>(), "room.pgm");
    EXPECT_EQ(yaml["mode"].as<std::string>(), "trinary");
    EXPECT_EQ(yaml["negate"].as<int>(), 0);
    back.resolution = yaml["resolution"].as<double>();
    back.origin = Eigen::Vector2d(yaml["origin"][0].as<double>(), yaml["origin"][1].as<double>());
    EXPECT_DOUBLE_EQ(yaml["origin"][2].as<double>(), 0.0);
    // The loader's thresholds read our three values back as what they are: occ = (255 - pixel) / 255.
    const double occupied = yaml["occupied_thresh"].as<double>(), free = yaml["free_thresh"].as<double>();
    const auto occ = [](int pixel) { return (255.0 - pixel) / 255.0; };
    EXPECT_GT(occ(kPgmOccupied), occupied);
    EXPECT_LT(occ(kPgmFree), free);
    EXPECT_TRUE(occ(kPgmUnknown) >= free && occ(kPgmUnknown) <= occupied);
    back.image = cv::imread((dir / "room.pgm").string(), cv::IMREAD_UNCHANGED);
    EXPECT_EQ(back.image.type(), CV_8UC1);
    // The run folder's PNG holds the same pixels, in far fewer bytes for a grid of mostly one value.
    {
        std::ofstream png(dir / "room.png", std::ios::binary);
        WritePng(png, grid, 0.25);
    }
    const cv::Mat from_png = cv::imread((dir / "room.png").string(), cv::IMREAD_UNCHANGED);
    EXPECT_EQ(from_png.type(), CV_8UC1);
    EXPECT_EQ(cv::countNonZero(from_png != back.image), 0);
    EXPECT_LT(fs::file_size(dir / "room.png"), fs::file_size(dir / "room.pgm") / 4);
    return back;
}

TEST(OccupancyGrid, TracedRoomReadsBackWithWallsWhereTheyAreAndFreeSpaceInside) {
    test::TempDir dir;
    const OccupancyGrid grid = ScannedRoom(0.05);
    const ReadBack back = WriteAndRead(grid, dir.path());
    ASSERT_EQ(back.image.cols, grid.width());
    ASSERT_EQ(back.image.rows, grid.height());
    EXPECT_DOUBLE_EQ(back.resolution, 0.05);
    EXPECT_NEAR(back.origin.x(), -0.5, 1e-9);
    EXPECT_NEAR(back.origin.y(), -0.5, 1e-9);
    // Every wall is occupied where it is, along its whole length: the cell on either side of the line
    // (a ray ends on the line, rounding puts it in one of the two).
    const auto wall = [&](const Eigen::Vector2d& on_line, const Eigen::Vector2d& across) {
        return back.At(on_line - 0.001 * across) == kPgmOccupied || back.At(on_line + 0.001 * across) == kPgmOccupied;
    };
    for (double s = 0.3; s < 5.7; s += 0.1) {
        EXPECT_TRUE(wall({0.0, s}, Eigen::Vector2d::UnitX())) << "x = 0 wall at y = " << s;
        EXPECT_TRUE(wall({10.0, s}, Eigen::Vector2d::UnitX())) << "x = 10 wall at y = " << s;
    }
    for (double s = 0.3; s < 9.7; s += 0.1) {
        EXPECT_TRUE(wall({s, 0.0}, Eigen::Vector2d::UnitY())) << "y = 0 wall at x = " << s;
        EXPECT_TRUE(wall({s, 6.0}, Eigen::Vector2d::UnitY())) << "y = 6 wall at x = " << s;
    }
    // Inside is free, outside never observed.
    for (double x = 0.5; x < 9.5; x += 0.25) {
        for (double y = 0.5; y < 5.5; y += 0.25) EXPECT_EQ(back.At({x, y}), kPgmFree) << x << ", " << y;
    }
    EXPECT_EQ(back.At({-0.3, 3.0}), kPgmUnknown);
    EXPECT_EQ(back.At({10.3, -0.3}), kPgmUnknown);
}

TEST(OccupancyGrid, WallsAreOneCellThick) {
    // A single wall: across it, occupied cells form one run of at most two cells (a line on a cell border).
    test::TempDir dir;
    const ReadBack back = WriteAndRead(ScannedRoom(0.05), dir.path());
    for (double y = 0.5; y < 5.5; y += 0.5) {
        int occupied = 0;
        for (double x = -0.45; x < 1.0; x += 0.05) occupied += back.At({x + 0.025, y}) == kPgmOccupied;
        EXPECT_GE(occupied, 1) << y;
        EXPECT_LE(occupied, 2) << y;
    }
}

TEST(OccupancyGrid, AnImageNameWithYamlSyntaxIsQuoted) {
    const OccupancyGrid grid(Eigen::AlignedBox2d(Eigen::Vector2d(0, 0), Eigen::Vector2d(1, 1)), 0.5);
    std::ostringstream yaml;
    WriteMapYaml(yaml, grid, "lab: \"A\" #2.pgm");
    EXPECT_EQ(YAML::Load(yaml.str())["image"].as<std::string>(), "lab: \"A\" #2.pgm");
}

TEST(OccupancyGrid, ExtentBeyondTheCellLimitCoarsensTheResolution) {
    const Eigen::AlignedBox2d extent(Eigen::Vector2d(0, 0), Eigen::Vector2d(1000.0, 10.0));
    EXPECT_DOUBLE_EQ(FittingResolution(extent, 0.05, 8192), 0.2);  // 0.1 needs 10,001 cells
    EXPECT_DOUBLE_EQ(FittingResolution(extent, 0.5, 8192), 0.5);
    const OccupancyGrid grid(extent, FittingResolution(extent, 0.05, 8192));
    EXPECT_LE(grid.width(), 8192);
}

TEST(OccupancyGrid, RaysOutsideTheGridOrNotFiniteAreSkipped) {
    OccupancyGrid grid(Eigen::AlignedBox2d(Eigen::Vector2d(0, 0), Eigen::Vector2d(1, 1)), 0.1);
    grid.AddRay({0.5, 0.55}, {3.0, 0.55});  // leaves the grid: the inside part is traced, no hit
    grid.AddRay({0.5, 0.5}, {std::nan(""), 0.5});
    grid.AddRay({0.5, 0.5}, {1e300, 0.5});
    int hits = 0, misses = 0;
    for (int y = 0; y < grid.height(); ++y) {
        for (int x = 0; x < grid.width(); ++x) {
            hits += int(grid.hits(x, y));
            misses += int(grid.misses(x, y));
        }
    }
    EXPECT_EQ(hits, 0);
    EXPECT_EQ(misses, 6);  // cells 5..10 of row 5 (the grid is 11 cells wide)
}

}  // namespace
}  // namespace revisit
