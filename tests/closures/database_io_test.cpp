#include <gtest/gtest.h>

#include <fstream>

#include "closures/database_io.hpp"
#include "core/error.hpp"
#include "test_support.hpp"

namespace revisit {
namespace {

std::filesystem::path TempFile(const std::string& name) {
    return std::filesystem::temp_directory_path() / ("revisit_closures_" + std::to_string(::getpid()) + "_" + name);
}

struct Session {
    std::vector<LocalMap> earlier;  // session 1: three places
    LocalMap revisit;               // session 2: the second place again, from another pose
    Eigen::Isometry3d T_query_ref;  // revisit frame <- earlier[1] frame
};

const Session& MakeSession() {
    static const Session s = [] {
        Session s;
        const auto world = test::MakeBoxWorld(77, 200.0, 200);
        for (int i = 0; i < 3; ++i) {
            s.earlier.push_back(test::SimulateLocalMap(world, test::StraightRoute(-150.0 + 120.0 * i, 0.0, 0.0), i, i));
        }
        s.revisit = test::SimulateLocalMap(world, test::StraightRoute(-22.0, 3.0, 0.4), 0, 9);
        s.T_query_ref = s.revisit.T_world_map.inverse() * s.earlier[1].T_world_map;
        return s;
    }();
    return s;
}

TEST(ClosureDatabase, SaveLoadThenANewSessionRelocalizesAgainstTheOldOne) {
    const auto& s = MakeSession();
    auto config = ClosureDetectorConfig::Paper();
    // Verify every voted map: with only three maps the paper's top-half rule keeps one, chosen by votes
    // that barely differ between these synthetic places.
    config.selection = CandidateSelection::kAllAboveMin;
    ClosureDetector first(config);
    for (const auto& map : s.earlier) EXPECT_TRUE(first.AddMap(map).empty());
    const auto file = TempFile("db.bin");
    SaveDatabase(first, file);

    ClosureDetector loaded = LoadDatabase(file, config);
    std::filesystem::remove(file);
    ASSERT_EQ(loaded.maps().size(), 3u);
    EXPECT_EQ(loaded.tree().size(), first.tree().size());
    EXPECT_EQ(loaded.AllDescriptors(), first.AllDescriptors());
    EXPECT_EQ(loaded.maps()[1].keypoints, first.maps()[1].keypoints);
    const cv::Mat a = first.Image(2), b = loaded.Image(2);
    ASSERT_FALSE(b.empty());
    EXPECT_EQ(cv::norm(a, b, cv::NORM_L1), 0.0);

    // The new session's map 0 matches the old session's map 1 although it is among the "last 3" maps:
    // the skip-recent rule applies within a session only.
    const auto closures = loaded.AddMap(s.revisit);
    ASSERT_EQ(closures.size(), 1u);
    EXPECT_EQ(closures[0].ref_id, 1);
    EXPECT_EQ(closures[0].ref_session, 0);
    EXPECT_EQ(closures[0].query_session, 1);
    EXPECT_LT(test::TranslationError(closures[0].T_query_ref, s.T_query_ref), 0.5);
    EXPECT_LT(test::YawError(closures[0].T_query_ref, s.T_query_ref), 1.0 * M_PI / 180.0);
}

void ExpectLoadError(const std::filesystem::path& file, const ClosureDetectorConfig& config, const std::string& what) {
    try {
        LoadDatabase(file, config);
        ADD_FAILURE() << "no error for " << what;
    } catch (const DatasetError& e) {
        EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
        EXPECT_EQ(e.file(), file);
    }
}

TEST(ClosureDatabase, RefusesMismatchedOrCorruptFilesWithAClearError) {
    const auto& s = MakeSession();
    const auto config = ClosureDetectorConfig::Paper();
    ClosureDetector detector(config);
    detector.AddMap(s.earlier[0]);
    const auto file = TempFile("bad.bin");
    SaveDatabase(detector, file);
    std::string bytes;
    {
        std::ifstream in(file, std::ios::binary);
        bytes.assign(std::istreambuf_iterator<char>(in), {});
    }
    auto write = [&](const std::string& content) { std::ofstream(file, std::ios::binary | std::ios::trunc) << content; };

    ExpectLoadError(file, ClosureDetectorConfig::Later(), "different configuration");
    std::string flipped = bytes;
    flipped[bytes.size() / 2] ^= 0x10;
    write(flipped);
    ExpectLoadError(file, config, "checksum");
    write(bytes.substr(0, bytes.size() - 100));
    ExpectLoadError(file, config, "truncated");
    std::string version = bytes;
    version[8] = 7;
    write(version);
    ExpectLoadError(file, config, "version 7");
    write("hello world, not a database");
    ExpectLoadError(file, config, "bad magic");
    std::filesystem::remove(file);
    ExpectLoadError(file, config, "no such file");
    std::filesystem::create_directory(file);  // a folder where the database should be
    ExpectLoadError(file, config, "is a folder, expected a file");
    std::filesystem::remove(file);
}

}  // namespace
}  // namespace revisit
