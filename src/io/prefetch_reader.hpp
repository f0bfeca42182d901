#pragma once
/// Reading overlapped with processing (issue 19): a reader that reads ahead on its own thread into a
/// bounded queue. Scans come out in the inner reader's order, errors at the scan where the inner
/// reader threw, and Info() / Stats() describe what the consumer has taken so far, exactly as the
/// inner reader would after the same number of Next() calls: nothing depends on how far it read ahead.
#include <condition_variable>
#include <cstddef>
#include <deque>
#include <exception>
#include <memory>
#include <mutex>
#include <thread>

#include "io/reader.hpp"

namespace revisit {

class PrefetchReader : public Reader {
  public:
    /// Reads up to `depth` scans ahead of the consumer (memory: depth scans).
    explicit PrefetchReader(std::unique_ptr<Reader> inner, std::size_t depth = 4);
    ~PrefetchReader() override;
    PrefetchReader(const PrefetchReader&) = delete;
    PrefetchReader& operator=(const PrefetchReader&) = delete;

    std::optional<Scan> Next() override;
    /// The inner reader's, before the first Next() only (then the read-ahead thread owns it): false after.
    bool SkipTo(std::size_t index) override;
    const DatasetInfo& Info() const override { return info_; }

  private:
    struct Item {
        std::optional<Scan> scan;      ///< nullopt: the end (or an error)
        std::exception_ptr error;
        ReadStats stats;               ///< the inner reader's after this scan
        DatasetInfo info;
    };
    void Produce();

    std::unique_ptr<Reader> inner_;
    const std::size_t depth_;
    DatasetInfo info_;
    std::mutex mutex_;
    std::condition_variable changed_;
    std::deque<Item> queue_;
    bool stop_ = false;
    bool ended_ = false;  ///< the consumer has taken the last item
    std::thread thread_;  ///< started by the first Next()
};

}  // namespace revisit
