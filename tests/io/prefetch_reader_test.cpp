// Reading ahead on a thread (issue 19) changes nothing the consumer sees: order, Info/Stats after each
// scan, the error at the scan where the inner reader failed, early stops.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdio>
#include <filesystem>

#include "core/error.hpp"
#include "io/cloud_files.hpp"
#include "io/prefetch_reader.hpp"
#include "test_data.hpp"

namespace revisit {
namespace {

/// `count` scans of `index + 1` points; throws DatasetError at scan `fail_at` (if below count).
class CountingReader : public Reader {
  public:
    CountingReader(std::size_t count, std::size_t fail_at, std::atomic<std::size_t>* reads)
        : count_(count), fail_at_(fail_at), reads_(reads) {
        info_.format = "fake";
    }
    std::optional<Scan> Next() override {
        if (reads_) ++*reads_;
        if (next_ == fail_at_) throw DatasetError("fake", "damaged at scan " + std::to_string(next_));
        if (next_ >= count_) return std::nullopt;
        Scan scan;
        scan.index = next_++;
        scan.points.assign(scan.index + 1, Eigen::Vector3f::Constant(float(scan.index)));
        stats_.scans++;
        stats_.points += scan.points.size();
        info_.num_scans = stats_.scans;  // like a rawlog: counted while reading
        return scan;
    }
    const DatasetInfo& Info() const override { return info_; }

  private:
    std::size_t count_, fail_at_, next_ = 0;
    std::atomic<std::size_t>* reads_;
    DatasetInfo info_;
};

TEST(PrefetchReader, SameScansStatsAndInfoAsTheInnerReaderAfterEveryScan) {
    PrefetchReader reader(std::make_unique<CountingReader>(50, 1000, nullptr), 3);
    EXPECT_EQ(reader.Info().format, "fake");
    std::size_t points = 0;
    for (std::size_t i = 0; i < 50; ++i) {
        const auto scan = reader.Next();
        ASSERT_TRUE(scan);
        EXPECT_EQ(scan->index, i);
        EXPECT_EQ(scan->points.size(), i + 1);
        points += i + 1;
        // What the consumer has taken, not how far the thread has read.
        EXPECT_EQ(reader.Stats().scans, i + 1);
        EXPECT_EQ(reader.Stats().points, points);
        EXPECT_EQ(reader.Info().num_scans, i + 1);
    }
    EXPECT_FALSE(reader.Next());
    EXPECT_FALSE(reader.Next());
}

TEST(PrefetchReader, SkipsWithTheInnerReaderOnlyBeforeReadingAhead) {
    // A stream cannot skip: false, and nothing was read.
    std::atomic<std::size_t> reads{0};
    PrefetchReader stream(std::make_unique<CountingReader>(10, 1000, &reads), 2);
    EXPECT_FALSE(stream.SkipTo(5));
    EXPECT_EQ(reads.load(), 0u);
    // A folder can, until the read-ahead thread owns it.
    test::TempDir dir;
    std::filesystem::create_directories(dir / "velodyne");
    for (int i = 0; i < 4; ++i) {
        char name[16];
        std::snprintf(name, sizeof(name), "%06d.bin", i);
        Scan scan;
        scan.points.assign(std::size_t(i + 1), Eigen::Vector3f::Constant(float(i)));
        scan.intensities.assign(scan.points.size(), 0.f);
        SaveKittiBin(dir / "velodyne" / name, scan);
    }
    PrefetchReader folder(OpenDataset(dir.path()), 2);
    ASSERT_TRUE(folder.SkipTo(2));
    EXPECT_EQ(folder.Stats().scans, 2u);
    const auto scan = folder.Next();
    ASSERT_TRUE(scan);
    EXPECT_EQ(scan->index, 2u);
    EXPECT_EQ(scan->points.size(), 3u);
    EXPECT_EQ(folder.Stats().scans, 3u);
    EXPECT_FALSE(folder.SkipTo(3));  // reading ahead: the caller reads on
    EXPECT_EQ(folder.Next()->index, 3u);
}

TEST(PrefetchReader, ErrorComesAtTheScanWhereTheInnerReaderFailed) {
    PrefetchReader reader(std::make_unique<CountingReader>(50, 7, nullptr), 4);
    for (std::size_t i = 0; i < 7; ++i) ASSERT_EQ(reader.Next()->index, i);
    try {
        reader.Next();
        FAIL() << "no error";
    } catch (const DatasetError& e) {
        EXPECT_NE(std::string(e.what()).find("damaged at scan 7"), std::string::npos);
    }
    EXPECT_FALSE(reader.Next());
}

TEST(PrefetchReader, ReadsABoundedDistanceAheadAndStopsWhenDestroyedEarly) {
    std::atomic<std::size_t> reads{0};
    {
        PrefetchReader reader(std::make_unique<CountingReader>(100000, 1000000, &reads), 4);
        ASSERT_TRUE(reader.Next());
        for (int wait = 0; wait < 200 && reads < 5; ++wait) std::this_thread::sleep_for(std::chrono::milliseconds(1));
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
        EXPECT_LE(reads.load(), 1u + 4u + 1u);  // the one taken, a full queue, one in flight
    }  // destroyed with the queue full: must not hang
    EXPECT_LT(reads.load(), 10u);
}

}  // namespace
}  // namespace revisit
