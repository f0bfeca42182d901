#pragma once
/// Progress of long work on stderr: one rewritten line with a bar on a terminal, plain periodic
/// lines otherwise (logs, CI), nothing when quiet.
#include <chrono>
#include <cstddef>
#include <functional>  // std::ref, to pass a CountedProgress as a callback
#include <optional>
#include <ostream>
#include <string>
#include <utility>

namespace revisit {

class Progress {
  public:
    enum class Mode { kTerminal, kPlain, kQuiet };

    /// `total` may be unknown (rawlogs): then no bar and no ETA.
    Progress(std::ostream& out, Mode mode, std::optional<std::size_t> total, std::string unit = "scans");

    /// Terminal when stderr is a tty, plain otherwise, quiet when asked.
    static Mode DetectMode(bool quiet);

    /// `extra` is appended, e.g. "maps 12  closures 3". Throttled: cheap to call every item.
    void Update(std::size_t done, const std::string& extra = "");
    /// A line of its own (a warning), printed even when quiet, without breaking the bar.
    void Message(const std::string& line);
    /// Clears the bar (terminal) and prints the final rate.
    void Finish(std::size_t done, const std::string& extra = "");
    /// Starts the clock again: the rate and the ETA count from now (after work that was not the items',
    /// such as the scans read and dropped before --from).
    void Restart();

    /// "1:02:03" or "2:03".
    static std::string FormatDuration(double seconds);

  private:
    std::string Line(std::size_t done, const std::string& extra, double elapsed) const;

    std::ostream& out_;
    Mode mode_;
    std::optional<std::size_t> total_;
    std::string unit_;
    std::chrono::steady_clock::time_point start_;
    std::chrono::steady_clock::time_point last_print_;
    bool printed_ = false;
};

/// Progress of work that reports (done, total) as it goes and knows its total only then (a callback's
/// arguments): made with the first report, finished (its final line) when done reaches total, and made
/// anew by a report after that (the proximity pass's rounds each count their own pairs). Pass it as the
/// callback with std::ref.
class CountedProgress {
  public:
    CountedProgress(std::ostream& out, Progress::Mode mode, std::string unit) : out_(out), mode_(mode), unit_(std::move(unit)) {}
    void operator()(std::size_t done, std::size_t total);

  private:
    std::ostream& out_;
    Progress::Mode mode_;
    std::string unit_;
    std::optional<Progress> progress_;
};

}  // namespace revisit
