#pragma once
/// The writing discipline for every file the tool writes: the bytes go to a temporary created
/// exclusively in the same folder (a fresh random name, O_EXCL | O_NOFOLLOW: a link or file planted
/// under any name is never opened), every write is checked (a full disk is reported as such, naming
/// the file), and only a complete file is renamed over the final name. rename(2) replaces whatever
/// is at the final name, a symbolic link included, instead of writing through it. A failing run
/// leaves no half-written file behind.
#include <filesystem>
#include <functional>
#include <ostream>
#include <string_view>

namespace revisit {

/// Writes `bytes` to `file` all or nothing. Throws DatasetError naming `file` and the system's reason
/// (e.g. "No space left on device"); on failure the temporary is removed and `file` is untouched.
void WriteFileAtomically(const std::filesystem::path& file, std::string_view bytes);

/// The same for text or binary produced by `fill` into a stream (kept in memory until complete).
void WriteFileAtomically(const std::filesystem::path& file, const std::function<void(std::ostream&)>& fill);

/// For a file written while it grows (a log followed with `tail -f`), so it cannot go through a
/// temporary: removes whatever has the name `file` (a link is removed, never its target; a folder is
/// refused), then creates `file` exclusively without following links. Returns the open descriptor
/// (write only, close-on-exec); throws DatasetError naming the file.
int CreateFileExclusively(const std::filesystem::path& file);

/// A temporary next to `file`, created exclusively (see above), for writers that stream (zlib,
/// MRPT): write through descriptor() or ReleaseDescriptor(), then Commit() renames it over `file`.
/// Destroyed without Commit(), it removes the temporary.
class TemporaryPath {
  public:
    explicit TemporaryPath(std::filesystem::path file);
    ~TemporaryPath();
    TemporaryPath(const TemporaryPath&) = delete;
    TemporaryPath& operator=(const TemporaryPath&) = delete;

    const std::filesystem::path& path() const { return temporary_; }
    const std::filesystem::path& target() const { return file_; }
    /// The temporary's open descriptor (write only), owned by this object; -1 once released.
    int descriptor() const { return fd_; }
    /// Hands the descriptor to a writer that closes it itself (gzdopen); checking that close is then its job.
    int ReleaseDescriptor();
    /// Closes the descriptor if still owned (a deferred write error is thrown, naming the file), then
    /// renames the temporary over the final name; throws DatasetError naming the file on failure.
    void Commit();

  private:
    std::filesystem::path file_;
    std::filesystem::path temporary_;
    int fd_ = -1;
    bool committed_ = false;
};

}  // namespace revisit
