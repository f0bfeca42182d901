#include "evaluation/statistics.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace revisit {
namespace {

TEST(ComputeStatistics, MatchesNumpyDefinitions) {
    const auto stats = ComputeStatistics({4.0, 1.0, 3.0, 2.0});
    EXPECT_EQ(stats.count, 4u);
    EXPECT_DOUBLE_EQ(stats.mean, 2.5);
    EXPECT_DOUBLE_EQ(stats.median, 2.5);
    EXPECT_DOUBLE_EQ(stats.rmse, std::sqrt(30.0 / 4.0));
    EXPECT_DOUBLE_EQ(stats.std, std::sqrt(1.25));  // ddof = 0
    EXPECT_DOUBLE_EQ(stats.min, 1.0);
    EXPECT_DOUBLE_EQ(stats.max, 4.0);
    EXPECT_DOUBLE_EQ(stats.sse, 30.0);
    EXPECT_DOUBLE_EQ(ComputeStatistics({5.0, 1.0, 2.0}).median, 2.0);
    EXPECT_EQ(ComputeStatistics({}).count, 0u);
}

}  // namespace
}  // namespace revisit
