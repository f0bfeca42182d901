#pragma once
/// Text from the data (a rawlog's sensor label, a topic name, a file name) reaches the terminal only
/// as printable text: control characters (ESC and the others below 0x20 but newline, tab and
/// carriage return; DEL; the C1 controls U+0080..U+009F) are written as `\xNN`, so a label cannot
/// clear the screen, set the window title or fake an output line.
#include <streambuf>
#include <string>
#include <string_view>

namespace revisit {

/// `text` with every control character but '\n', '\t' and '\r' written as \xNN (C1 controls as \xc2\xNN).
std::string Printable(std::string_view text);

/// A value from the data printed inside a line (a label, a topic name): Printable, and line breaks
/// and tabs escaped too, so it cannot start a fake line of output.
std::string PrintableField(std::string_view text);

/// A stream buffer that filters everything written through it as Printable does, into `target`.
/// `revisit` installs it on std::cout and std::cerr for the whole run.
class PrintableStreambuf : public std::streambuf {
  public:
    explicit PrintableStreambuf(std::streambuf* target) : target_(target) {}
    ~PrintableStreambuf() override;

  protected:
    int_type overflow(int_type c) override;
    std::streamsize xsputn(const char* s, std::streamsize n) override;
    int sync() override;

  private:
    bool Put(unsigned char c);
    std::streambuf* target_;
    bool after_c2_ = false;  ///< the last byte was 0xC2: a C1 control may follow
};

/// Installs PrintableStreambuf on std::cout and std::cerr (idempotent).
void FilterTerminalOutput();

}  // namespace revisit
