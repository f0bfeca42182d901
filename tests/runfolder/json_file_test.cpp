/// JSON files never fail on text that is not UTF-8, and paths read back byte for byte.
#include <gtest/gtest.h>

#include "runfolder/json_file.hpp"
#include "test_data.hpp"

namespace revisit {
namespace {
namespace fs = std::filesystem;

TEST(JsonFile, PathsThatAreNotUtf8AreWrittenAndReadBackExactly) {
    test::TempDir dir;
    const fs::path latin1 = "/data/caf\xe9/scans";  // Latin-1 e-acute: not UTF-8
    const fs::path utf8 = "/data/caf\xc3\xa9/scans";
    EXPECT_FALSE(IsValidUtf8(latin1.string()));
    EXPECT_TRUE(IsValidUtf8(utf8.string()));
    EXPECT_FALSE(IsValidUtf8("\xc0\xaf"));          // overlong '/'
    EXPECT_FALSE(IsValidUtf8("\xed\xa0\x80"));      // a UTF-16 surrogate
    EXPECT_FALSE(IsValidUtf8("ab\xe2\x82"));        // cut in the middle of a character
    nlohmann::json j;
    PutPath(j, "dataset", latin1);
    PutPath(j, "gt_file", utf8);
    j["label"] = std::string("LIDAR\xff");  // any other text: replaced, never an exception
    ASSERT_NO_THROW(WriteJsonFile(dir / "run_options.json", j));
    const auto read = nlohmann::json::parse(test::ReadFile(dir / "run_options.json"));
    EXPECT_EQ(GetPath(read, "dataset"), latin1);
    EXPECT_EQ(GetPath(read, "gt_file"), utf8);
    EXPECT_FALSE(read.contains("gt_file_bytes"));  // a UTF-8 path is written as it is
    EXPECT_EQ(read.at("dataset").get<std::string>(), "/data/caf\xef\xbf\xbd/scans");  // readable, U+FFFD
    EXPECT_EQ(read.at("label").get<std::string>(), "LIDAR\xef\xbf\xbd");
}

}  // namespace
}  // namespace revisit
