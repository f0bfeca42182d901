/// `revisit eval RUN --relations FILE`: the relation metric of a run's trajectories, as a user calls it.
#include <gtest/gtest.h>

#include <fstream>

#include "cli.hpp"
#include "test_data.hpp"

namespace revisit {
namespace {
namespace fs = std::filesystem;
using test::Quote;
using test::RunCli;

/// A run folder with two trajectories along x at 1 m/s, stamped 0..4 s: the odometry 10% short, the
/// corrected one exact.
void WriteRun(const fs::path& root) {
    fs::create_directories(root);
    std::ofstream(root / "run.json") << "{}\n";
    std::ofstream odometry(root / "poses_odometry_tum.txt"), corrected(root / "poses_corrected_tum.txt");
    for (int i = 0; i < 5; ++i) {
        odometry << i << ' ' << 0.9 * i << " 0 0 0 0 0 1\n";
        corrected << i << ' ' << 1.0 * i << " 0 0 0 0 0 1\n";
    }
}

TEST(CliRelations, PrintsTheRelationErrorsOfBothTrajectories) {
    test::TempDir dir;
    WriteRun(dir / "run");
    // Two relations of 1 m and one of 2 m forward: the odometry errs 0.1, 0.1 and 0.2 m.
    std::ofstream(dir / "walk.relations") << "# t1 t2 x y z roll pitch yaw\n0 1 1 0 0 0 0 0\n1 2 1 0 0 0 0 0\n2 4 2 0 0 0 0 0\n9 10 1 0 0 0 0 0\n";
    const auto result = RunCli("eval " + Quote((dir / "run").string()) + " --relations " + Quote((dir / "walk.relations").string()));
    ASSERT_EQ(result.exit_code, 0) << result.output;
    EXPECT_NE(result.output.find("4 relations"), std::string::npos) << result.output;
    // odometry: 3 used, 1 unmatched (no pose at 9-10 s), mean translation error 0.4 / 3 m.
    EXPECT_NE(result.output.find("odometry        3          1           0.1333"), std::string::npos) << result.output;
    EXPECT_NE(result.output.find("corrected       3          1           0.0000"), std::string::npos) << result.output;
}

TEST(CliRelations, ABadRelationsFileNamesTheLine) {
    test::TempDir dir;
    WriteRun(dir / "run");
    std::ofstream(dir / "bad.relations") << "0 1 1 0 0 0 0 0\n1 2 x\n";
    const auto result = RunCli("eval " + Quote((dir / "run").string()) + " --relations " + Quote((dir / "bad.relations").string()));
    EXPECT_NE(result.exit_code, 0);
    EXPECT_NE(result.output.find("bad.relations:2"), std::string::npos) << result.output;
}

}  // namespace
}  // namespace revisit
