#pragma once
/// Ctrl-C stops long work cleanly: the first SIGINT sets a flag that loops check, so everything
/// computed so far is written (marked incomplete); a second SIGINT exits at once.

#include <stdexcept>

namespace revisit {

/// Thrown by work that stops on Ctrl-C without a partial result to keep (the report: the old one stays).
struct Interrupted : std::runtime_error {
    using std::runtime_error::runtime_error;
};

/// Installs the handler (idempotent) and clears the flag.
void InstallInterruptHandler();
bool InterruptRequested();

}  // namespace revisit
