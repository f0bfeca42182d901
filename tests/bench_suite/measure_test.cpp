// The harness statistics: median, min, max, spread, warm-up and repetition counts. No timing asserts.
#include <gtest/gtest.h>

#include <cmath>

#include "bench_suite/measure.hpp"

namespace revisit {
namespace {

Measurement WithSamples(std::vector<double> samples) {
    Measurement m;
    m.name = "x";
    m.samples = std::move(samples);
    return Summarize(m);
}

TEST(Summarize, MedianOfOddAndEvenCounts) {
    EXPECT_DOUBLE_EQ(WithSamples({5, 1, 3}).median, 3.0);
    EXPECT_DOUBLE_EQ(WithSamples({4, 1, 3, 10}).median, 3.5);
    EXPECT_DOUBLE_EQ(WithSamples({7}).median, 7.0);
}

TEST(Summarize, MinMaxAndRelativeSpread) {
    const auto m = WithSamples({12, 8, 10, 9, 11});
    EXPECT_DOUBLE_EQ(m.min, 8.0);
    EXPECT_DOUBLE_EQ(m.max, 12.0);
    EXPECT_DOUBLE_EQ(m.median, 10.0);
    EXPECT_DOUBLE_EQ(m.spread, 0.2);  // half the range (2) over the median (10)
    EXPECT_DOUBLE_EQ(WithSamples({3, 3, 3}).spread, 0.0);
}

TEST(Summarize, OutlierMovesMaxNotMedian) {
    const auto m = WithSamples({10, 10, 11, 10, 500});
    EXPECT_DOUBLE_EQ(m.median, 10.0);
    EXPECT_DOUBLE_EQ(m.max, 500.0);
    EXPECT_GT(m.spread, 20.0);
}

TEST(Summarize, RejectsNoSamples) { EXPECT_THROW(WithSamples({}), std::invalid_argument); }

TEST(Measure, RunsWarmupThenRepetitionsAndKeepsOneSamplePerRepetition) {
    int calls = 0;
    const auto m = Measure("count", "ms/item", FigureKind::kMsPerItem, {2, 5}, [&] {
        ++calls;
        return 1.0;
    });
    EXPECT_EQ(calls, 7);
    EXPECT_EQ(m.samples.size(), 5u);
    EXPECT_EQ(m.name, "count");
    EXPECT_EQ(m.unit, "ms/item");
    for (double s : m.samples) EXPECT_GE(s, 0.0);
    EXPECT_LE(m.min, m.median);
    EXPECT_LE(m.median, m.max);
    EXPECT_FALSE(m.higher_is_better());
}

TEST(Measure, RateIsItemsOverTime) {
    // Real work of fixed size: the rate is positive, finite and flagged higher-is-better.
    volatile double sink = 0.0;
    const auto work = [&] {
        for (int i = 0; i < 200000; ++i) sink = sink + std::sqrt(double(i));
        return 1000.0;
    };
    const auto rate = Measure("rate", "items/s", FigureKind::kItemsPerSecond, {0, 3}, work);
    EXPECT_TRUE(rate.higher_is_better());
    EXPECT_GT(rate.median, 0.0);
    EXPECT_TRUE(std::isfinite(rate.median));
}

TEST(MeasureValue, KeepsTheValuesTheWorkReports) {
    double next = 1.0;
    const auto m = MeasureValue("v", "MiB", FigureKind::kAbsolute, {1, 3}, [&] { return next++; });
    // The warm-up consumed 1.0; samples are 2, 3, 4.
    EXPECT_EQ(m.samples, (std::vector<double>{2.0, 3.0, 4.0}));
    EXPECT_DOUBLE_EQ(m.median, 3.0);
}

}  // namespace
}  // namespace revisit
