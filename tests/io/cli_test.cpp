/// Black-box tests of `revisit info` and `revisit convert`.
#include <gtest/gtest.h>

#include <fstream>

#include "cli.hpp"
#include "io/reader.hpp"
#include "io/writer.hpp"
#include "read_all.hpp"
#include "test_data.hpp"

namespace revisit {
namespace {
using test::Quote;
using test::RunCli;

TEST(Cli, HelpTeachesEveryCommandWithExamples) {
    const auto root = RunCli("--help");
    EXPECT_EQ(root.exit_code, 0);
    EXPECT_NE(root.output.find("info"), std::string::npos);
    EXPECT_NE(root.output.find("convert"), std::string::npos);
    for (const char* command : {"info", "convert"}) {
        const auto help = RunCli(std::string(command) + " --help");
        EXPECT_EQ(help.exit_code, 0) << command;
        EXPECT_NE(help.output.find("Examples"), std::string::npos) << command;
    }
}

TEST(Cli, BadArgumentsExitNonZero) {
    EXPECT_NE(RunCli("").exit_code, 0);
    EXPECT_NE(RunCli("frobnicate").exit_code, 0);
    EXPECT_NE(RunCli("info").exit_code, 0);
    EXPECT_NE(RunCli("convert onlyone").exit_code, 0);
}

TEST(Cli, MissingDatasetNamesThePath) {
    const auto result = RunCli("info /nonexistent/revisit-data");
    EXPECT_EQ(result.exit_code, 1);
    EXPECT_NE(result.output.find("revisit: /nonexistent/revisit-data: no such file or folder"), std::string::npos)
        << result.output;
}

TEST(Cli, InfoOnSenaLoop) {
    const auto file = test::MrptDataset("2006-01ENE-21-SENA_Telecom Faculty_one_loop_only.rawlog");
    REVISIT_REQUIRE_DATA(file);
    const auto result = RunCli("info " + Quote(file.string()));
    EXPECT_EQ(result.exit_code, 0) << result.output;
    EXPECT_NE(result.output.find("scans:            225"), std::string::npos) << result.output;
    EXPECT_NE(result.output.find("(likely loops)"), std::string::npos) << result.output;
}

TEST(Cli, InfoOnARawlogWithoutScansFails) {
    const auto file = test::MrptDataset("kf-slam_6D_demo.rawlog");
    REVISIT_REQUIRE_DATA(file);
    const auto result = RunCli("info " + Quote(file.string()));
    EXPECT_EQ(result.exit_code, 1);
    EXPECT_NE(result.output.find("no range scans found"), std::string::npos) << result.output;
    EXPECT_NE(result.output.find("CObservationBearingRange x600"), std::string::npos) << result.output;
}

TEST(Cli, ASensorLabelWithTerminalEscapesIsPrintedEscaped) {
    test::TempDir dir;
    const auto file = dir / "label.rawlog";
    // Clear screen, a window title, and a fake line after a carriage return.
    const std::string label = "LIDAR\x1b[2J\x1b]0;owned\x07\rrevisit: all good";
    {
        auto writer = CreateRawlogWriter(file);
        for (int s = 0; s < 3; ++s) {
            Scan scan;
            scan.timestamp = s;
            scan.sensor_label = label;
            for (int i = 0; i < 50; ++i) scan.points.emplace_back(i * 0.2f, float(s), 0.3f);
            writer->Write(scan);
        }
        writer->Finish();
    }
    const auto result = RunCli("info " + Quote(file.string()));
    EXPECT_EQ(result.output.find('\x1b'), std::string::npos) << result.output;
    EXPECT_EQ(result.output.find('\x07'), std::string::npos) << result.output;
    EXPECT_NE(result.output.find("LIDAR\\x1b[2J\\x1b]0;owned\\x07\\x0drevisit: all good"), std::string::npos) << result.output;
}

TEST(Cli, ConvertKittiToRawlogAndBackIsBitExact) {
    const auto kitti = test::SharedData("kitti00_first16");
    REVISIT_REQUIRE_DATA(kitti);
    test::TempDir dir;
    const auto rawlog = dir / "k.rawlog.gz";
    const auto back = dir / "back";
    ASSERT_EQ(RunCli("convert " + Quote(kitti.string()) + " " + Quote(rawlog.string())).exit_code, 0);
    const auto to_kitti = RunCli("convert " + Quote(rawlog.string()) + " " + Quote(back.string()));
    ASSERT_EQ(to_kitti.exit_code, 0) << to_kitti.output;
    for (const char* name : {"000000.bin", "000007.bin", "000015.bin"}) {
        std::ifstream a(kitti / "velodyne" / name, std::ios::binary), b(back / "velodyne" / name, std::ios::binary);
        const std::string bytes_a((std::istreambuf_iterator<char>(a)), {}), bytes_b((std::istreambuf_iterator<char>(b)), {});
        EXPECT_EQ(bytes_a.size(), bytes_b.size()) << name;
        EXPECT_TRUE(bytes_a == bytes_b) << name << " differs after the round trip";
    }
    // Reference poses survive in the LiDAR frame.
    auto original = OpenDataset(kitti), copy = OpenDataset(back);
    while (auto a = original->Next()) {
        const auto b = copy->Next();
        ASSERT_TRUE(b && b->T_world_sensor);
        EXPECT_LT((a->T_world_sensor->matrix() - b->T_world_sensor->matrix()).norm(), 1e-6);
        EXPECT_NEAR(a->timestamp, b->timestamp, 1e-6);
    }
}

TEST(Cli, ConvertRefusesToOverwriteUnlessForced) {
    const auto file = test::MrptDataset("localization_demo.rawlog");
    REVISIT_REQUIRE_DATA(file);
    test::TempDir dir;
    const auto out = dir / "out";
    std::filesystem::create_directories(out);
    std::ofstream(out / "precious.txt") << "keep me";
    const auto refused = RunCli("convert " + Quote(file.string()) + " " + Quote(out.string()));
    EXPECT_EQ(refused.exit_code, 1);
    EXPECT_NE(refused.output.find("--force"), std::string::npos) << refused.output;
    EXPECT_FALSE(std::filesystem::exists(out / "velodyne"));
    const auto forced = RunCli("convert " + Quote(file.string()) + " " + Quote(out.string()) + " --force");
    EXPECT_EQ(forced.exit_code, 0) << forced.output;
    EXPECT_TRUE(std::filesystem::exists(out / "precious.txt"));
    EXPECT_EQ(OpenDataset(out)->Info().num_scans, 37u);
}

TEST(Cli, ConvertEachRecordingToKittiAndRawlog) {
    // The shared walk as ROS 1 bag, MCAP and rosbag2 folder: each converts to a KITTI folder with the
    // walk's very point bytes, its reference poses and its stamps, and to a rawlog with the same scans.
    const auto walk = test::SharedData("livox_handheld_walk");
    const auto bags = test::SharedData("bags");
    REVISIT_REQUIRE_DATA(walk);
    REVISIT_REQUIRE_DATA(bags);
    const auto original = test::ReadAllScans(walk);
    ASSERT_EQ(original.size(), 266u);
    test::TempDir dir;
    for (const char* name : {"livox_walk.bag", "livox_walk.mcap", "livox_walk_db3"}) {
        const auto kitti = dir / (std::string(name) + ".kitti");
        const auto rawlog = dir / (std::string(name) + ".rawlog");
        const auto to_kitti = RunCli("convert " + Quote((bags / name).string()) + " " + Quote(kitti.string()));
        ASSERT_EQ(to_kitti.exit_code, 0) << to_kitti.output;
        for (const char* bin : {"000000.bin", "000133.bin", "000265.bin"}) {
            std::ifstream a(walk / "velodyne" / bin, std::ios::binary), b(kitti / "velodyne" / bin, std::ios::binary);
            const std::string bytes_a((std::istreambuf_iterator<char>(a)), {}), bytes_b((std::istreambuf_iterator<char>(b)), {});
            EXPECT_TRUE(!bytes_a.empty() && bytes_a == bytes_b) << name << ": " << bin << " differs";
        }
        const auto converted = test::ReadAllScans(kitti);
        ASSERT_EQ(converted.size(), original.size()) << name;
        for (std::size_t i = 0; i < original.size(); i += 19) {
            ASSERT_TRUE(converted[i].T_world_sensor) << name << " scan " << i;
            EXPECT_LT((converted[i].T_world_sensor->matrix() - original[i].T_world_sensor->matrix()).norm(), 1e-5) << name << " scan " << i;
            // The recording's stamps are absolute, the walk's times.txt starts at 0.
            EXPECT_NEAR(converted[i].timestamp - converted[0].timestamp, original[i].timestamp - original[0].timestamp, 1e-6);
        }
        const auto to_rawlog = RunCli("convert " + Quote((bags / name).string()) + " " + Quote(rawlog.string()));
        ASSERT_EQ(to_rawlog.exit_code, 0) << to_rawlog.output;
        const auto from_rawlog = test::ReadAllScans(rawlog);
        ASSERT_EQ(from_rawlog.size(), original.size()) << name;
        EXPECT_EQ(from_rawlog[133].points.size(), original[133].points.size()) << name;
    }
}

TEST(Cli, ConvertCarmenLogToKittiGivesTheSharedConversionsScans) {
    const auto log = test::SharedData("carmen/seattle-corrected.log.gz");
    const auto reference = test::SharedData("carmen_kitti/seattle");
    REVISIT_REQUIRE_DATA(log);
    REVISIT_REQUIRE_DATA(reference);
    test::TempDir dir;
    const auto out = dir / "seattle";
    const auto converted = RunCli("convert " + Quote(log.string()) + " " + Quote(out.string()));
    ASSERT_EQ(converted.exit_code, 0) << converted.output;
    const auto ours = test::ReadAllScans(out), theirs = test::ReadAllScans(reference);
    ASSERT_EQ(ours.size(), theirs.size());
    for (std::size_t i = 0; i < ours.size(); i += 37) {
        ASSERT_EQ(ours[i].points.size(), theirs[i].points.size()) << "scan " << i;
        for (std::size_t k = 0; k < ours[i].points.size(); k += 17) {
            EXPECT_LT((ours[i].points[k] - theirs[i].points[k]).norm(), 1e-4) << "scan " << i << " point " << k;
        }
    }
}

}  // namespace
}  // namespace revisit
