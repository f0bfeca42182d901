#pragma once
/// Records appended to an exclusive scratch file and read back by number, each compressed on its own
/// (zstd, fast level): the evaluation's voxel sets and ScanContext descriptors of a long run are ~11 KB
/// per scan raw and compress ~2.5x. Only the records' places stay in memory (16 bytes each).
#include "core/atomic_file.hpp"

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <vector>

namespace revisit {

class ScratchRecords {
  public:
    /// Creates the temporary beside `file` (TemporaryPath: a fresh name, no link followed, nothing at
    /// `file` touched); the destructor removes it. `what` names a record in messages.
    ScratchRecords(const std::filesystem::path& file, const char* what);
    ~ScratchRecords();
    ScratchRecords(const ScratchRecords&) = delete;
    ScratchRecords& operator=(const ScratchRecords&) = delete;

    /// Appends record size(). Throws DatasetError naming the file on a write error (e.g. a full disk).
    void Append(const void* data, std::size_t bytes);
    std::size_t size() const { return places_.size(); }
    /// Record `k` exactly as appended. Safe to call from several threads.
    std::vector<std::uint8_t> Read(std::size_t k) const;
    /// The temporary file (for messages about a record's contents).
    const std::filesystem::path& path() const { return scratch_.path(); }

  private:
    struct Place {
        std::uint64_t offset = 0;      ///< [bytes] of the compressed record in the file
        std::uint32_t stored = 0;      ///< [bytes] compressed
        std::uint32_t bytes = 0;       ///< [bytes] as appended
    };
    TemporaryPath scratch_;
    int read_fd_ = -1;
    const char* what_;
    std::vector<Place> places_;
    std::uint64_t end_ = 0;
};

}  // namespace revisit
