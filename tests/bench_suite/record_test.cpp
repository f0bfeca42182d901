// Records: JSON round trip, malformed input, comparison ratios and the printed tables.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "bench_suite/record.hpp"
#include "core/error.hpp"

namespace revisit {
namespace {

Measurement Figure(const std::string& name, FigureKind kind, std::vector<double> samples) {
    Measurement m;
    m.name = name;
    m.unit = kind == FigureKind::kItemsPerSecond ? "scans/s" : "ms/scan";
    m.kind = kind;
    m.samples = std::move(samples);
    m.note = "note of " + name;
    return Summarize(m);
}

BenchRecord Record(double odometry_ms, double reader_rate, double spread_fraction = 0.0) {
    BenchRecord r;
    r.suite = "quick";
    r.started_utc = "2026-11-22T08:00:00Z";
    r.machine.cores = 2;
    r.machine.threads = 2;
    r.machine.build_type = "Release";
    r.machine.cpu = "test cpu";
    r.duration_s = 123.5;
    r.peak_memory_kb = 4096;
    r.data_dir = "/data";
    r.skipped = {"something: absent"};
    const double d = spread_fraction;
    r.results.push_back(
        Figure("odometry/a", FigureKind::kMsPerItem, {odometry_ms * (1 - d), odometry_ms, odometry_ms * (1 + d)}));
    r.results.push_back(Figure("reader/b", FigureKind::kItemsPerSecond, {reader_rate, reader_rate}));
    return r;
}

TEST(RecordJson, RoundTripKeepsEveryField) {
    const BenchRecord r = Record(20.0, 500.0, 0.1);
    const BenchRecord back = RecordFromJson(RecordToJson(r));
    EXPECT_EQ(back.suite, r.suite);
    EXPECT_EQ(back.started_utc, r.started_utc);
    EXPECT_EQ(back.machine.cores, 2u);
    EXPECT_EQ(back.machine.build_type, "Release");
    EXPECT_EQ(back.machine.cpu, "test cpu");
    EXPECT_DOUBLE_EQ(back.duration_s, 123.5);
    EXPECT_EQ(back.peak_memory_kb, 4096u);
    EXPECT_EQ(back.skipped, r.skipped);
    ASSERT_EQ(back.results.size(), 2u);
    for (std::size_t i = 0; i < 2; ++i) {
        EXPECT_EQ(back.results[i].name, r.results[i].name);
        EXPECT_EQ(back.results[i].unit, r.results[i].unit);
        EXPECT_EQ(back.results[i].kind, r.results[i].kind);
        EXPECT_EQ(back.results[i].samples, r.results[i].samples);
        EXPECT_DOUBLE_EQ(back.results[i].median, r.results[i].median);
        EXPECT_DOUBLE_EQ(back.results[i].spread, r.results[i].spread);
        EXPECT_EQ(back.results[i].note, r.results[i].note);
    }
}

TEST(RecordJson, FileRoundTrip) {
    const auto file = std::filesystem::temp_directory_path() / "revisit_record_test.json";
    WriteRecord(file, Record(20.0, 500.0));
    EXPECT_EQ(ReadRecord(file).results.size(), 2u);
    std::filesystem::remove(file);
}

TEST(RecordJson, MalformedInputNamesTheSource) {
    EXPECT_THROW(RecordFromJson("{not json", "old.json"), DatasetError);
    EXPECT_THROW(RecordFromJson("{\"format\": \"something else\"}", "old.json"), DatasetError);
    EXPECT_THROW(RecordFromJson("{\"format\": \"revisit-bench-1\", \"suite\": \"quick\"}", "old.json"), DatasetError);
    try {
        RecordFromJson("[1, 2", "old.json");
        FAIL();
    } catch (const DatasetError& e) {
        EXPECT_NE(std::string(e.what()).find("old.json"), std::string::npos);
    }
    EXPECT_THROW(ReadRecord("/nonexistent/record.json"), DatasetError);
}

TEST(Compare, TimesAndRatesBothReportSpeedupAboveOneWhenFaster) {
    // Odometry went from 20 to 10 ms/scan (2x faster); the reader from 500 to 1000 scans/s (2x faster).
    const auto c = CompareRecords(Record(20.0, 500.0), Record(10.0, 1000.0));
    ASSERT_EQ(c.ratios.size(), 2u);
    EXPECT_DOUBLE_EQ(c.ratios[0].ratio, 0.5);
    EXPECT_DOUBLE_EQ(c.ratios[0].speedup, 2.0);
    EXPECT_DOUBLE_EQ(c.ratios[1].ratio, 2.0);
    EXPECT_DOUBLE_EQ(c.ratios[1].speedup, 2.0);
    EXPECT_NEAR(c.geometric_mean_speedup, 2.0, 1e-12);
    // Slower: speedup below one.
    const auto slower = CompareRecords(Record(10.0, 1000.0), Record(20.0, 800.0));
    EXPECT_DOUBLE_EQ(slower.ratios[0].speedup, 0.5);
    EXPECT_DOUBLE_EQ(slower.ratios[1].speedup, 0.8);
    EXPECT_NEAR(slower.geometric_mean_speedup, std::sqrt(0.4), 1e-12);
}

TEST(Compare, MatchesByNameAndListsTheRest) {
    BenchRecord old_record = Record(20.0, 500.0), new_record = Record(20.0, 500.0);
    old_record.results[1].name = "reader/old only";
    new_record.results.push_back(Figure("tree/new", FigureKind::kMsPerItem, {1.0}));
    const auto c = CompareRecords(old_record, new_record);
    ASSERT_EQ(c.ratios.size(), 1u);
    EXPECT_EQ(c.ratios[0].name, "odometry/a");
    EXPECT_DOUBLE_EQ(c.ratios[0].ratio, 1.0);
    EXPECT_EQ(c.only_old, std::vector<std::string>{"reader/old only"});
    EXPECT_EQ(c.only_new, (std::vector<std::string>{"reader/b", "tree/new"}));
}

TEST(Compare, SmallChangesWithinTheSpreadAreMarkedAsNoise) {
    const auto c = CompareRecords(Record(20.0, 500.0, 0.2), Record(19.0, 500.0, 0.2));
    EXPECT_NEAR(c.ratios[0].noise, 0.2, 1e-12);
    const std::string table = FormatComparison(c);
    EXPECT_NE(table.find("within noise"), std::string::npos);
    const std::string clear = FormatComparison(CompareRecords(Record(20.0, 500.0), Record(10.0, 250.0)));
    EXPECT_EQ(clear.find("within noise"), std::string::npos);
    EXPECT_NE(clear.find("2.00x"), std::string::npos);
    EXPECT_NE(clear.find("0.50x"), std::string::npos);
}

TEST(Compare, SlowerOnlyWhenEveryNewSampleIsWorseThanEveryOldOne) {
    // Old 18..22 ms, new 21..23 ms: the ranges overlap, a slowdown within the runs' spread.
    BenchRecord old_record = Record(20.0, 500.0, 0.1), overlap = Record(22.0, 500.0, 0.05);
    EXPECT_FALSE(CompareRecords(old_record, overlap).ratios[0].slower);
    // New 23.75..26.25 ms: above the old maximum of 22 ms.
    const auto c = CompareRecords(old_record, Record(25.0, 500.0, 0.05));
    EXPECT_TRUE(c.ratios[0].slower);
    EXPECT_FALSE(c.ratios[1].slower);
    EXPECT_EQ(c.slower, std::vector<std::string>{"odometry/a"});
    EXPECT_NE(FormatComparison(c).find("SLOWER"), std::string::npos);
    // Rates: slower when the new maximum is below the old minimum; faster never flags.
    EXPECT_TRUE(CompareRecords(Record(20.0, 500.0), Record(20.0, 400.0)).ratios[1].slower);
    EXPECT_TRUE(CompareRecords(Record(20.0, 500.0), Record(10.0, 1000.0)).slower.empty());
}

TEST(StageRatios, GeometricMeanPerStageWithTheWorstFigure) {
    // Reference: odometry figures 10 and 40 ms, tree 2 ms, reader 500 scans/s. New: odometry 5 ms (2x
    // faster) and 80 ms (2x slower), tree 1 ms (2x faster), reader 1500 scans/s (3x faster).
    BenchRecord reference = Record(10.0, 500.0), now = Record(5.0, 1500.0);
    reference.results.push_back(Figure("odometry/c", FigureKind::kMsPerItem, {40.0}));
    reference.results.push_back(Figure("tree/q", FigureKind::kMsPerItem, {2.0}));
    now.results.push_back(Figure("odometry/c", FigureKind::kMsPerItem, {80.0}));
    now.results.push_back(Figure("tree/q", FigureKind::kMsPerItem, {1.0}));
    const auto stages = StageRatios(CompareRecords(reference, now));
    ASSERT_EQ(stages.size(), 3u);
    EXPECT_EQ(stages[0].stage, "odometry");
    EXPECT_EQ(stages[0].figures, 2);
    EXPECT_NEAR(stages[0].geometric_mean_speedup, 1.0, 1e-12);  // sqrt(2 * 0.5)
    EXPECT_EQ(stages[0].worst_figure, "odometry/c");
    EXPECT_NEAR(stages[0].worst_speedup, 0.5, 1e-12);
    EXPECT_EQ(stages[0].slower, 1);
    EXPECT_EQ(stages[1].stage, "reader");
    EXPECT_NEAR(stages[1].geometric_mean_speedup, 3.0, 1e-12);
    EXPECT_EQ(stages[2].stage, "tree");
    EXPECT_NEAR(stages[2].geometric_mean_speedup, 2.0, 1e-12);
    EXPECT_EQ(stages[2].slower, 0);
    const std::string table = FormatStageRatios(stages);
    EXPECT_NE(table.find("odometry"), std::string::npos);
    EXPECT_NE(table.find("3.00x"), std::string::npos);
}

TEST(Format, TableListsEveryFigureMachineAndSkips) {
    const std::string table = FormatRecord(Record(20.0, 500.0));
    for (const char* needle :
         {"odometry/a", "reader/b", "ms/scan", "scans/s", "2 cores", "Release", "skipped: something"})
        EXPECT_NE(table.find(needle), std::string::npos) << needle;
}

}  // namespace
}  // namespace revisit
