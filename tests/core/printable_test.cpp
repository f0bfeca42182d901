/// Text from the data never drives the terminal: control characters are written as \xNN.
#include <gtest/gtest.h>

#include <sstream>

#include "core/printable.hpp"

namespace revisit {
namespace {

TEST(Printable, ControlCharactersAreEscapedAndTextKept) {
    // Clear screen, a window title (OSC ... BEL), a fake line after a carriage return, a C1 CSI.
    const std::string label = "LIDAR\x1b[2J\x1b]0;pwned\x07\r\nrevisit: done\x7f\xc2\x9b" "31m caf\xc3\xa9";
    EXPECT_EQ(Printable(label), "LIDAR\\x1b[2J\\x1b]0;pwned\\x07\r\nrevisit: done\\x7f\\xc2\\x9b" "31m caf\xc3\xa9");
    EXPECT_EQ(Printable("plain text\twith a tab\n"), "plain text\twith a tab\n");
    EXPECT_EQ(PrintableField("a\rfake line\n"), "a\\x0dfake line\\x0a");
    // The stream filter gives the same, whatever the pieces it is written in.
    std::ostringstream target;
    {
        PrintableStreambuf filter(target.rdbuf());
        std::ostream out(&filter);
        for (const char c : label) out << c;
        out << std::flush;
    }
    EXPECT_EQ(target.str(), Printable(label));
    std::ostringstream whole;
    {
        PrintableStreambuf filter(whole.rdbuf());
        std::ostream(&filter) << label << "\xc2";  // a lone 0xC2 at the end is written when the filter closes
    }
    EXPECT_EQ(whole.str(), Printable(label) + "\xc2");
}

}  // namespace
}  // namespace revisit
