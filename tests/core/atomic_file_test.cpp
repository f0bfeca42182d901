/// The writing discipline (core/atomic_file.hpp) on a real full disk: a failed write names the file
/// and the reason, and leaves neither a half-written file nor a temporary behind.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "small_disk.hpp"
#include "test_data.hpp"

namespace revisit {
namespace {
namespace fs = std::filesystem;

std::size_t CountFiles(const fs::path& folder) {
    std::size_t n = 0;
    for ([[maybe_unused]] const auto& entry : fs::directory_iterator(folder)) ++n;
    return n;
}

TEST(AtomicFile, ReplacesTheFileAndLeavesNoTemporary) {
    test::TempDir dir;
    WriteFileAtomically(dir / "a.txt", std::string_view("first\n"));
    WriteFileAtomically(dir / "a.txt", [](std::ostream& out) { out << "second " << 2 << '\n'; });
    EXPECT_EQ(test::ReadFile(dir / "a.txt"), "second 2\n");
    EXPECT_EQ(CountFiles(dir.path()), 1u);
}

TEST(AtomicFile, FullDiskNamesTheFileAndKeepsThePreviousContent) {
    test::SmallDisk disk(64 * 1024);
    if (!disk.mounted()) GTEST_SKIP() << "cannot mount a small tmpfs (needs root); the full-disk path is untested here";
    const fs::path file = disk.path() / "run.json";
    WriteFileAtomically(file, std::string_view("{\"complete\": true}\n"));
    const std::string big(1 << 20, 'x');
    try {
        WriteFileAtomically(file, big);
        FAIL() << "a 1 MiB write on a 64 KiB disk succeeded";
    } catch (const DatasetError& e) {
        EXPECT_NE(std::string(e.what()).find("No space left on device"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find(file.string()), std::string::npos) << e.what();
    }
    EXPECT_EQ(test::ReadFile(file), "{\"complete\": true}\n");  // untouched, not truncated
    EXPECT_EQ(CountFiles(disk.path()), 1u);               // the temporary is gone
}

TEST(AtomicFile, TemporaryPathIsRemovedUnlessCommitted) {
    test::TempDir dir;
    fs::path temporary;
    {
        TemporaryPath path(dir / "out.rawlog");
        temporary = path.path();
        std::ofstream(temporary) << "partial";
        EXPECT_EQ(temporary.parent_path(), dir.path());
    }
    EXPECT_FALSE(fs::exists(temporary));
    EXPECT_FALSE(fs::exists(dir / "out.rawlog"));
    TemporaryPath path(dir / "out.rawlog");
    std::ofstream(path.path()) << "complete";
    path.Commit();
    EXPECT_EQ(test::ReadFile(dir / "out.rawlog"), "complete");
}

}  // namespace
}  // namespace revisit
