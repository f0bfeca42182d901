/// Black-box tests of `revisit info` and `revisit convert`.
#include <gtest/gtest.h>

#include <fstream>

#include "cli.hpp"
#include "io/reader.hpp"
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

}  // namespace
}  // namespace revisit
