#include "pipeline/interrupt.hpp"

#include <unistd.h>

#include <atomic>
#include <csignal>
#include <cstdlib>

namespace revisit {
namespace {
std::atomic<bool> interrupted{false};

extern "C" void OnInterrupt(int) {
    if (interrupted.exchange(true)) std::_Exit(130);  // second Ctrl-C: the user insists
    const char message[] = "\nrevisit: interrupted; finishing and writing what was computed (Ctrl-C again to abort)\n";
    [[maybe_unused]] const auto written = write(STDERR_FILENO, message, sizeof(message) - 1);
}
}  // namespace

void InstallInterruptHandler() {
    interrupted = false;
    std::signal(SIGINT, OnInterrupt);
    std::signal(SIGTERM, OnInterrupt);
}

bool InterruptRequested() { return interrupted.load(); }

}  // namespace revisit
