#include "pipeline/progress.hpp"

#include <unistd.h>

#include <cstdio>
#include <iomanip>
#include <sstream>

namespace revisit {

Progress::Progress(std::ostream& out, Mode mode, std::optional<std::size_t> total, std::string unit)
    : out_(out), mode_(mode), total_(total), unit_(std::move(unit)), start_(std::chrono::steady_clock::now()),
      last_print_(start_) {}

Progress::Mode Progress::DetectMode(bool quiet) {
    if (quiet) return Mode::kQuiet;
    return isatty(STDERR_FILENO) ? Mode::kTerminal : Mode::kPlain;
}

std::string Progress::FormatDuration(double seconds) {
    const long s = static_cast<long>(seconds + 0.5);
    char text[32];
    if (s >= 3600) std::snprintf(text, sizeof(text), "%ld:%02ld:%02ld", s / 3600, (s / 60) % 60, s % 60);
    else std::snprintf(text, sizeof(text), "%ld:%02ld", s / 60, s % 60);
    return text;
}

std::string Progress::Line(std::size_t done, const std::string& extra, double elapsed) const {
    std::ostringstream line;
    const double rate = elapsed > 0.0 ? done / elapsed : 0.0;
    if (total_ && *total_ > 0) {
        const double fraction = std::min(1.0, static_cast<double>(done) / *total_);
        if (mode_ == Mode::kTerminal) {
            constexpr int kWidth = 24;
            const int filled = static_cast<int>(fraction * kWidth);
            line << '[' << std::string(filled, '#') << std::string(kWidth - filled, '.') << "] ";
        }
        line << done << '/' << *total_ << ' ' << unit_ << " (" << static_cast<int>(100 * fraction) << "%)";
    } else {
        line << done << ' ' << unit_;
    }
    // A rate over less than a second is noise (work that was cached or trivial: millions per second).
    constexpr double kMinRateSeconds = 1.0;
    if (elapsed >= kMinRateSeconds) {
        line << "  " << std::fixed << std::setprecision(1) << rate << ' ' << unit_ << "/s";
        if (total_ && rate > 0.0 && done < *total_) line << "  ETA " << FormatDuration((*total_ - done) / rate);
    }
    if (!extra.empty()) line << "  " << extra;
    return line.str();
}

void Progress::Update(std::size_t done, const std::string& extra) {
    if (mode_ == Mode::kQuiet) return;
    const auto now = std::chrono::steady_clock::now();
    const double since_print = std::chrono::duration<double>(now - last_print_).count();
    // A terminal redraws 5 times a second; a log gets a line every 10 s.
    if (since_print < (mode_ == Mode::kTerminal ? 0.2 : 10.0)) return;
    last_print_ = now;
    const std::string line = Line(done, extra, std::chrono::duration<double>(now - start_).count());
    if (mode_ == Mode::kTerminal) out_ << "\r\033[K" << line << std::flush;
    else out_ << line << '\n' << std::flush;
    printed_ = true;
}

void Progress::Message(const std::string& line) {
    if (mode_ == Mode::kTerminal && printed_) out_ << "\r\033[K";
    out_ << line << '\n' << std::flush;
    last_print_ = std::chrono::steady_clock::time_point{};  // redraw the bar at the next update
}

void Progress::Finish(std::size_t done, const std::string& extra) {
    if (mode_ == Mode::kQuiet) return;
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    if (mode_ == Mode::kTerminal && printed_) out_ << "\r\033[K";
    out_ << Line(done, extra, elapsed) << "  in " << FormatDuration(elapsed) << '\n' << std::flush;
}

void Progress::Restart() { start_ = last_print_ = std::chrono::steady_clock::now(); }

void CountedProgress::operator()(std::size_t done, std::size_t total) {
    if (!progress_) progress_.emplace(out_, mode_, total, unit_);
    if (done < total) {
        progress_->Update(done);
        return;
    }
    progress_->Finish(done);
    progress_.reset();
}

}  // namespace revisit
