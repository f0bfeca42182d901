#pragma once
/// The ScanContext descriptors of a whole sequence without holding them: each scan's bins and sector
/// key go to a scratch file as they are made (ScratchRecords, compressed), only the ring keys (what the
/// search tree needs) stay in memory, and a candidate's descriptor is read back when its distance is
/// computed. 100,000 scans of 20 x 60 bins are ~500 MB as descriptors in memory, ~10 MB of ring keys
/// here and ~2 KB per scan of disk.
#include "evaluation/scan_context.hpp"
#include "evaluation/scratch_records.hpp"

#include <Eigen/Core>
#include <cstddef>
#include <filesystem>
#include <vector>

namespace revisit {

class ScanContextFile {
  public:
    /// Creates an exclusive temporary beside `file` (ScratchRecords) for descriptors of `rows` x `cols`
    /// bins. The destructor removes it.
    ScanContextFile(const std::filesystem::path& file, int rows, int cols);
    ScanContextFile(const ScanContextFile&) = delete;
    ScanContextFile& operator=(const ScanContextFile&) = delete;

    /// Appends the next scan's descriptor (of the size given at construction). Throws on a write error
    /// (e.g. a full disk), naming the file.
    void Add(const ScanContextDescriptor& descriptor);
    std::size_t size() const { return ring_keys_.size(); }
    const std::vector<Eigen::VectorXf>& ring_keys() const { return ring_keys_; }
    /// Scan `scan`'s descriptor, exactly as added. Safe to call from several threads.
    ScanContextDescriptor Get(std::size_t scan) const;

  private:
    ScratchRecords records_;
    int rows_ = 0;
    int cols_ = 0;
    std::vector<Eigen::VectorXf> ring_keys_;
};

}  // namespace revisit
