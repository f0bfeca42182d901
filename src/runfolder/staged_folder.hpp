#pragma once
/// A folder that is rebuilt whole (a run's report/): the new content is written into a fresh folder
/// beside the old one and swapped in only when complete, so a failure or Ctrl-C half-way leaves the
/// old content as it was. Creating, swapping and removing follow the writing and deleting
/// disciplines (core/atomic_file.hpp, core/owned_files.hpp).
#include <filesystem>
#include <string>
#include <vector>

namespace revisit {

class StagedFolder {
  public:
    /// Creates `.NAME.staged-RANDOM` beside `target` exclusively (mkdtemp: nothing planted there is
    /// used). `own_extensions` (".html") are the kinds of file the writer puts there: only they are
    /// removed, from the staged folder when it is abandoned and from the old folder after the swap.
    /// Refuses a `target` that is a symbolic link (DatasetError).
    StagedFolder(std::filesystem::path target, std::vector<std::string> own_extensions);
    /// Without Commit(): the staged files are removed, `target` is untouched.
    ~StagedFolder();
    StagedFolder(const StagedFolder&) = delete;
    StagedFolder& operator=(const StagedFolder&) = delete;

    const std::filesystem::path& path() const { return staged_; }
    const std::filesystem::path& target() const { return target_; }

    /// Puts the staged folder at `target`: the old folder is renamed aside, the staged one renamed in,
    /// then the old one's own files and the old folder removed. Returns the empty path, or where the
    /// old folder was kept because it held files revisit did not write (`NAME.previous-RANDOM`).
    std::filesystem::path Commit();

  private:
    std::filesystem::path target_;
    std::filesystem::path staged_;
    std::vector<std::string> own_extensions_;
    bool committed_ = false;
};

}  // namespace revisit
