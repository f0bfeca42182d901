// What a user reads while long work runs: the count, the share, and a rate only once it means something.
#include <gtest/gtest.h>

#include <chrono>
#include <functional>
#include <sstream>
#include <thread>

#include "pipeline/progress.hpp"

namespace revisit {
namespace {

TEST(Progress, ARateNeedsASecondOfWork) {
    // Work that was cached or trivial ends within milliseconds: its "rate" would be millions per second.
    std::ostringstream instant;
    Progress quick(instant, Progress::Mode::kPlain, 35814, "segments");
    quick.Finish(35814);
    EXPECT_EQ(instant.str(), "35814/35814 segments (100%)  in 0:00\n");

    std::ostringstream timed;
    Progress slow(timed, Progress::Mode::kPlain, 10, "items");
    std::this_thread::sleep_for(std::chrono::milliseconds(1100));
    slow.Finish(10);
    EXPECT_NE(timed.str().find("10/10 items (100%)  "), std::string::npos) << timed.str();
    EXPECT_NE(timed.str().find(" items/s  in 0:01\n"), std::string::npos) << timed.str();
}

TEST(CountedProgress, EachCountToItsTotalGetsOneFinalLine) {
    // The proximity pass's two rounds report their own totals through one callback.
    std::ostringstream out;
    CountedProgress rounds(out, Progress::Mode::kPlain, "map pairs");
    const std::function<void(std::size_t, std::size_t)> callback = std::ref(rounds);
    for (std::size_t done = 1; done <= 3; ++done) callback(done, 3);
    for (std::size_t done = 1; done <= 2; ++done) callback(done, 2);
    EXPECT_EQ(out.str(), "3/3 map pairs (100%)  in 0:00\n2/2 map pairs (100%)  in 0:00\n");
}

TEST(Progress, QuietPrintsNothingButMessages) {
    std::ostringstream out;
    Progress quiet(out, Progress::Mode::kQuiet, 10, "items");
    quiet.Update(5);
    quiet.Finish(10);
    EXPECT_EQ(out.str(), "");
    quiet.Message("warning: something the user must see");
    EXPECT_EQ(out.str(), "warning: something the user must see\n");
}

}  // namespace
}  // namespace revisit
