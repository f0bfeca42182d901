/// A closure's detail file (closures/NNNN.json): the matches only, read back exactly and checked against
/// the maps' keypoint counts; files of older runs that still carry the keypoints read as before.
#include <gtest/gtest.h>

#include <fstream>

#include "core/error.hpp"
#include "runfolder/run_files.hpp"
#include "test_data.hpp"

namespace revisit {
namespace {
namespace fs = std::filesystem;

/// A detected pair as the detector leaves it: both maps' keypoints and a few matches, half inliers.
Closure DetectedPair() {
    Closure c;
    for (int i = 0; i < 300; ++i) c.query_keypoints.emplace_back(10.5f + 0.25f * i, 40.f - 0.125f * i);
    for (int i = 0; i < 280; ++i) c.ref_keypoints.emplace_back(12.f + 0.5f * i, 3.75f + 0.25f * i);
    for (int i = 0; i < 40; ++i) {
        c.matches.push_back(FeatureMatch{7 * i, 279 - 6 * i, 20 + i});
        c.inlier_mask.push_back(static_cast<std::uint8_t>(i % 2));
    }
    return c;
}

TEST(ClosureDetail, HoldsTheMatchesOnlyAndReadsThemBackExactly) {
    test::TempDir dir;
    const Closure written = DetectedPair();
    WriteClosureDetail(dir / "0000.json", written, false);
    const std::string text = test::ReadFile(dir / "0000.json");
    EXPECT_EQ(text.find("keypoints"), std::string::npos) << "the keypoints are database.bin's";
    EXPECT_LT(text.size(), 1000u);

    Closure read;
    ReadClosureDetail(dir / "0000.json", read, 300, 280);
    ASSERT_EQ(read.matches.size(), written.matches.size());
    for (std::size_t i = 0; i < read.matches.size(); ++i) {
        EXPECT_EQ(read.matches[i].query_keypoint, written.matches[i].query_keypoint);
        EXPECT_EQ(read.matches[i].ref_keypoint, written.matches[i].ref_keypoint);
        EXPECT_EQ(read.matches[i].distance, written.matches[i].distance);
    }
    EXPECT_EQ(read.inlier_mask, written.inlier_mask);
    EXPECT_TRUE(read.query_keypoints.empty());
}

TEST(ClosureDetail, AMatchBeyondTheMapsKeypointsIsAnErrorNamingTheFile) {
    test::TempDir dir;
    WriteClosureDetail(dir / "0001.json", DetectedPair(), false);
    Closure read;
    // The reference map has 280 keypoints; index 279 is the last. A map of 250 cannot hold the matches.
    try {
        ReadClosureDetail(dir / "0001.json", read, 300, 250);
        FAIL() << "a match index beyond the map's keypoints was accepted";
    } catch (const DatasetError& e) {
        EXPECT_NE(std::string(e.what()).find("0001.json"), std::string::npos) << e.what();
    }
}

TEST(ClosureDetail, KeypointsNotInTheDatabaseAreKeptAndBoundTheMatches) {
    // A pair across sessions: its keypoints are not the run's database maps', so the file keeps them.
    test::TempDir dir;
    const Closure written = DetectedPair();
    WriteClosureDetail(dir / "0004.json", written, true);
    Closure read;
    ReadClosureDetail(dir / "0004.json", read, 0, 0);
    EXPECT_EQ(read.query_keypoints, written.query_keypoints);
    EXPECT_EQ(read.ref_keypoints, written.ref_keypoints);
    EXPECT_EQ(read.matches.size(), written.matches.size());
}

TEST(ClosureDetail, AnOlderFileWithKeypointsIsReadWithThem) {
    test::TempDir dir;
    std::ofstream(dir.path() / "0002.json") << R"({"query_keypoints":[[1.5,2.0],[3.0,4.0]],"ref_keypoints":[[5.0,6.0]],)"
                                     << R"("matches":[[1,0,17,1],[0,0,30,0]]})";
    Closure read;
    ReadClosureDetail(dir / "0002.json", read, 0, 0);  // the file's own keypoints bound the matches
    ASSERT_EQ(read.query_keypoints.size(), 2u);
    EXPECT_FLOAT_EQ(read.query_keypoints[1].y(), 4.f);
    ASSERT_EQ(read.matches.size(), 2u);
    EXPECT_EQ(read.matches[0].query_keypoint, 1);
    EXPECT_EQ(read.inlier_mask, (std::vector<std::uint8_t>{1, 0}));

    std::ofstream(dir.path() / "0003.json") << R"({"query_keypoints":[[1.5,2.0]],"ref_keypoints":[[5.0,6.0]],"matches":[[1,0,17,1]]})";
    EXPECT_THROW(ReadClosureDetail(dir / "0003.json", read, 1000, 1000), DatasetError);
}

}  // namespace
}  // namespace revisit
