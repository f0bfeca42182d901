// Opening an input file names the file and the problem.
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "core/error.hpp"
#include "core/input_file.hpp"
#include "test_data.hpp"

namespace revisit {
namespace {

std::string ErrorOf(const std::filesystem::path& file) {
    try {
        OpenForReading(file);
    } catch (const DatasetError& error) {
        return error.what();
    }
    return "";
}

TEST(OpenForReading, NamesAFolderAMissingFileAndReadsARealOne) {
    test::TempDir dir;
    std::filesystem::create_directory(dir / "run.json");
    const std::string folder = ErrorOf(dir / "run.json");
    EXPECT_NE(folder.find((dir / "run.json").string()), std::string::npos) << folder;
    EXPECT_NE(folder.find("is a folder, expected a file"), std::string::npos) << folder;
    EXPECT_NE(ErrorOf(dir / "missing.json").find("no such file"), std::string::npos);
    std::ofstream(dir / "ok.txt") << "42\n";
    auto in = OpenForReading(dir / "ok.txt");
    int value = 0;
    in >> value;
    EXPECT_EQ(value, 42);
}

}  // namespace
}  // namespace revisit
