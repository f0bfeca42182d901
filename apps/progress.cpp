#include <unistd.h>

#include <iostream>

#include "commands.hpp"

namespace revisit::app {
namespace {
bool progress_shown = false;
}

void ShowProgress(const std::string& text) {
    if (!isatty(STDERR_FILENO)) return;
    std::cerr << "\r\033[K" << text << std::flush;
    progress_shown = true;
}

void EndProgress() {
    if (!progress_shown) return;
    std::cerr << "\r\033[K" << std::flush;
    progress_shown = false;
}

}  // namespace revisit::app
