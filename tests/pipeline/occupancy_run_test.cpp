/// occupancy.png + occupancy.yaml of whole runs, read back with OpenCV and yaml-cpp as a navigation
/// stack reads them: a 2D laser's rays traced at the corrected poses, a 3D run's band of heights.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include <opencv2/imgcodecs.hpp>
#include <yaml-cpp/yaml.h>

#include "cli.hpp"
#include "exports/occupancy_grid.hpp"
#include "io/trajectory_io.hpp"
#include "runfolder/planar_scans.hpp"
#include "runfolder/run_files.hpp"
#include "sim_dataset.hpp"
#include "test_data.hpp"

namespace revisit {
namespace {
namespace fs = std::filesystem;
using test::Quote;
using test::RunCli;

/// A grid as map_server loads it: the image and the metres of its pixels.
struct ServedMap {
    cv::Mat image;
    double resolution = 0.0;
    Eigen::Vector2d origin = Eigen::Vector2d::Zero();

    explicit ServedMap(const fs::path& yaml_file) {
        const YAML::Node yaml = YAML::LoadFile(yaml_file.string());
        resolution = yaml["resolution"].as<double>();
        origin = {yaml["origin"][0].as<double>(), yaml["origin"][1].as<double>()};
        image = cv::imread((yaml_file.parent_path() / yaml["image"].as<std::string>()).string(), cv::IMREAD_UNCHANGED);
    }
    /// The pixel of a point, or -1 outside the image.
    int At(const Eigen::Vector2d& point) const {
        const int column = static_cast<int>(std::floor((point.x() - origin.x()) / resolution));
        const int row = image.rows - 1 - static_cast<int>(std::floor((point.y() - origin.y()) / resolution));
        if (column < 0 || row < 0 || column >= image.cols || row >= image.rows) return -1;
        return image.at<uchar>(row, column);
    }
    int Count(int value) const { return cv::countNonZero(image == value); }
};

TEST(OccupancyRun, ALaserRunTracesItsBeamsAtTheCorrectedPoses) {
    test::TempDir dir;
    const fs::path rawlog = dir / "office.rawlog";
    ASSERT_EQ(RunCli("simulate --preset indoor-2d-360 --scans 150 --quiet --out " + Quote(rawlog.string())).exit_code, 0);
    const fs::path out = dir / "run";
    const auto run = RunCli("run " + Quote(rawlog.string()) + " --quiet --set output.write_report=false --out " + Quote(out.string()));
    ASSERT_EQ(run.exit_code, 0) << run.output;

    const ServedMap map(out / "occupancy.yaml");
    ASSERT_FALSE(map.image.empty());
    EXPECT_DOUBLE_EQ(map.resolution, 0.05);
    const RunFolder folder = RunFolder::Open(out);
    const RunState state = ReadRunState(folder);
    // Where the robot drove is free; where its beams ended (at the corrected poses) is mostly a wall.
    std::size_t on_free = 0, ends = 0, on_occupied = 0;
    for (const auto& T : state.corrected) on_free += map.At(T.translation().head<2>()) == kPgmFree;
    EXPECT_GE(on_free, state.corrected.size() * 95 / 100);
    for (const auto& summary : state.maps) {
        for (const auto& scan : ReadPlanarScans(folder, summary.id)) {
            const Eigen::Isometry3d& T_world_sensor = state.corrected.at(scan.position);
            for (const auto& p : scan.points_in_sensor) {
                ++ends;
                on_occupied += map.At((T_world_sensor * Eigen::Vector3d(p.x(), p.y(), 0.0)).head<2>()) == kPgmOccupied;
            }
        }
    }
    ASSERT_GT(ends, 150u * 100u) << "every scan's beams were kept";
    EXPECT_GE(double(on_occupied), 0.8 * double(ends));
    EXPECT_GT(map.Count(kPgmFree), map.Count(kPgmOccupied));
    EXPECT_GT(map.Count(kPgmUnknown), 0);

    // `revisit export` redraws it at another cell from the run folder alone: the same origin, half the size.
    const fs::path coarse = dir / "coarse.pgm";
    const auto exported = RunCli("export " + Quote(out.string()) + " --format occupancy --set occupancy.resolution=0.1 --out " +
                                 Quote(coarse.string()));
    ASSERT_EQ(exported.exit_code, 0) << exported.output;
    // Every map read twice (the extent, then the cells), counted where the user sees it.
    const std::string passes = std::to_string(2 * ReadRunState(RunFolder::Open(out)).maps.size());
    EXPECT_NE(exported.output.find(passes + "/" + passes + " map passes (occupancy grid) (100%)"), std::string::npos) << exported.output;
    const ServedMap redrawn(dir / "coarse.yaml");
    EXPECT_DOUBLE_EQ(redrawn.resolution, 0.1);
    EXPECT_NEAR((redrawn.origin - map.origin).norm(), 0.0, 1e-9);
    EXPECT_NEAR(redrawn.image.cols, map.image.cols / 2.0, 1.0);
    EXPECT_NEAR(redrawn.image.rows, map.image.rows / 2.0, 1.0);
    // Only the grid's own keys: the graph and the closures are the run's.
    const auto refused = RunCli("export " + Quote(out.string()) + " --format occupancy --set odometry.voxel_size=1");
    EXPECT_NE(refused.exit_code, 0);
    EXPECT_NE(refused.output.find("occupancy.* keys only"), std::string::npos) << refused.output;
    // A damaged scans file is named with its offset, never read as a shorter map.
    fs::resize_file(PlanarScansFile(folder, 0), fs::file_size(PlanarScansFile(folder, 0)) - 3);
    const auto damaged = RunCli("export " + Quote(out.string()) + " --format occupancy --out " + Quote((dir / "d.pgm").string()));
    EXPECT_NE(damaged.exit_code, 0);
    EXPECT_NE(damaged.output.find("scans_0000.bin"), std::string::npos) << damaged.output;
}

TEST(OccupancyRun, ADriveMarksItsRoadFreeAndTheBuildingsAlongItOccupied) {
    test::TempDir dir;
    const fs::path out = dir / "run";
    const auto run = RunCli("run " + Quote(test::TinySimDataset().string()) + " --to 400 --quiet --set output.write_report=false --out " +
                            Quote(out.string()));
    ASSERT_EQ(run.exit_code, 0) << run.output;
    const ServedMap map(out / "occupancy.yaml");
    ASSERT_FALSE(map.image.empty());
    const RunState state = ReadRunState(RunFolder::Open(out));
    // The simulated streets are flat: the first map's levelled frame keeps x and y within the cell. The
    // road is never an obstacle; most of it is seen (16 beams leave gaps between their ground rings).
    std::size_t on_free = 0, on_occupied = 0;
    for (const auto& T : state.corrected) {
        on_free += map.At(T.translation().head<2>()) == kPgmFree;
        on_occupied += map.At(T.translation().head<2>()) == kPgmOccupied;
    }
    EXPECT_GE(on_free, state.corrected.size() * 7 / 10);
    EXPECT_LE(on_occupied, state.corrected.size() * 3 / 100);
    EXPECT_GT(map.Count(kPgmOccupied), 100);
    EXPECT_GT(map.Count(kPgmFree), map.Count(kPgmOccupied));
}

}  // namespace
}  // namespace revisit
