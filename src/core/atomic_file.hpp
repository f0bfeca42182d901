#pragma once
/// The writing discipline for every file the tool writes: the bytes go to a temporary name in the
/// same folder, every write is checked (a full disk is reported as such, naming the file), and only a
/// complete file is renamed over the final name. A failing run leaves no half-written file behind.
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

/// A temporary name next to `file` for writers that need a path (MRPT streams, OpenCV): write there,
/// then Commit() renames it over `file`. Destroyed without Commit(), it removes the temporary.
class TemporaryPath {
  public:
    explicit TemporaryPath(std::filesystem::path file);
    ~TemporaryPath();
    TemporaryPath(const TemporaryPath&) = delete;
    TemporaryPath& operator=(const TemporaryPath&) = delete;

    const std::filesystem::path& path() const { return temporary_; }
    const std::filesystem::path& target() const { return file_; }
    /// Renames the temporary over the final name; throws DatasetError naming the file on failure.
    void Commit();

  private:
    std::filesystem::path file_;
    std::filesystem::path temporary_;
    bool committed_ = false;
};

}  // namespace revisit
