/// The writing discipline (core/atomic_file.hpp) on a real full disk: a failed write names the file
/// and the reason, and leaves neither a half-written file nor a temporary behind.
#include <gtest/gtest.h>
#include <unistd.h>

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

/// A file outside the folder being written, and links to it planted where a writer might open.
struct PlantedLinks {
    test::TempDir outside;
    fs::path victim = outside / "precious.txt";
    PlantedLinks() { std::ofstream(victim) << "mine"; }
};

TEST(AtomicFile, ALinkPlantedUnderAnyTemporaryNameIsNeverWrittenThrough) {
    PlantedLinks planted;
    test::TempDir dir;
    // Every name the temporary could have had with the process id and a counter.
    for (int n = 0; n < 2000; ++n)
        fs::create_symlink(planted.victim, dir / (".run.json.tmp-" + std::to_string(getpid()) + "-" + std::to_string(n)));
    fs::create_symlink(planted.victim, dir / "run.json");  // and the final name itself
    WriteFileAtomically(dir / "run.json", std::string_view("{}\n"));
    TemporaryPath streamed(dir / "run.json");
    EXPECT_EQ(::write(streamed.descriptor(), "{}\n", 3), 3);
    streamed.Commit();
    EXPECT_EQ(test::ReadFile(planted.victim), "mine");
    EXPECT_FALSE(fs::is_symlink(dir / "run.json"));  // the link was replaced, not followed
    EXPECT_EQ(test::ReadFile(dir / "run.json"), "{}\n");
    EXPECT_EQ(CountFiles(dir.path()), 2001u);  // the planted links and the file: no temporary left
}

TEST(AtomicFile, AGrowingFileReplacesALinkAtItsNameAndRefusesAFolder) {
    PlantedLinks planted;
    test::TempDir dir;
    fs::create_symlink(planted.victim, dir / "00_run.log");
    const int fd = CreateFileExclusively(dir / "00_run.log");
    ASSERT_GE(fd, 0);
    EXPECT_EQ(::write(fd, "log\n", 4), 4);
    ::close(fd);
    EXPECT_EQ(test::ReadFile(planted.victim), "mine");
    EXPECT_FALSE(fs::is_symlink(dir / "00_run.log"));
    EXPECT_EQ(test::ReadFile(dir / "00_run.log"), "log\n");
    fs::create_directory(dir / "a_folder.log");
    try {
        CreateFileExclusively(dir / "a_folder.log");
        FAIL() << "a folder was opened as a log";
    } catch (const DatasetError& e) {
        EXPECT_NE(std::string(e.what()).find("a_folder.log"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace revisit
