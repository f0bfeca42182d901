/// A folder rebuilt whole (a run's report/): swapped in only when complete, the old one kept on
/// failure, and nothing but the writer's own kinds of file ever removed.
#include <gtest/gtest.h>

#include <fstream>
#include <set>
#include <stdexcept>
#include <string>

#include "core/error.hpp"
#include "runfolder/staged_folder.hpp"
#include "test_data.hpp"

namespace revisit {
namespace {
namespace fs = std::filesystem;

std::set<std::string> Listing(const fs::path& folder) {
    std::set<std::string> names;
    for (const auto& entry : fs::directory_iterator(folder)) names.insert(entry.path().filename().string());
    return names;
}

void Write(const fs::path& file, const std::string& text) { std::ofstream(file) << text; }

TEST(StagedFolder, ReplacesTheOldFolderOnlyWhenCommitted) {
    test::TempDir dir;
    const fs::path report = dir / "report";
    fs::create_directories(report);
    Write(report / "index.html", "old");
    Write(report / "closure_0001.html", "old");
    {
        StagedFolder staged(report, {".html", ".png"});
        Write(staged.path() / "index.html", "half");
        // Abandoned (an error or Ctrl-C half-way): the old folder is as it was, the staged one gone.
    }
    EXPECT_EQ(Listing(dir.path()), std::set<std::string>{"report"});
    EXPECT_EQ(Listing(report), (std::set<std::string>{"closure_0001.html", "index.html"}));
    EXPECT_EQ(test::ReadFile(report / "index.html"), "old");
    {
        StagedFolder staged(report, {".html", ".png"});
        Write(staged.path() / "index.html", "new");
        Write(staged.path() / "map_top.png", "new");
        EXPECT_TRUE(staged.Commit().empty());
    }
    EXPECT_EQ(Listing(dir.path()), std::set<std::string>{"report"});
    EXPECT_EQ(Listing(report), (std::set<std::string>{"index.html", "map_top.png"}));  // the stale page is gone
    EXPECT_EQ(test::ReadFile(report / "index.html"), "new");
}

TEST(StagedFolder, KeepsFilesRevisitDidNotWriteAndNeverFollowsALink) {
    test::TempDir dir;
    const fs::path report = dir / "report";
    fs::create_directories(report);
    fs::create_directories(dir / "elsewhere");
    Write(dir / "elsewhere" / "photo.png", "mine");
    Write(report / "index.html", "old");
    Write(report / "notes.txt", "mine");
    fs::create_symlink(dir / "elsewhere" / "photo.png", report / "photo.png");
    StagedFolder staged(report, {".html", ".png"});
    Write(staged.path() / "index.html", "new");
    const fs::path kept = staged.Commit();
    ASSERT_FALSE(kept.empty());
    EXPECT_EQ(kept.parent_path(), dir.path());
    EXPECT_EQ(Listing(kept), (std::set<std::string>{"notes.txt", "photo.png"}));  // the old page went, the user's files stayed
    EXPECT_EQ(test::ReadFile(dir / "elsewhere" / "photo.png"), "mine");
    EXPECT_EQ(test::ReadFile(report / "index.html"), "new");

    // A target that is a link is refused before anything is created.
    fs::create_directory_symlink(dir / "elsewhere", dir / "linked");
    EXPECT_THROW(StagedFolder(dir / "linked", {".html"}), DatasetError);
    EXPECT_EQ(Listing(dir / "elsewhere"), std::set<std::string>{"photo.png"});
}

}  // namespace
}  // namespace revisit
