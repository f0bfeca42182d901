// What a user reads while long work runs: the count, the share, and a rate only once it means something.
#include <gtest/gtest.h>

#include <chrono>
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
