#pragma once
/// Ctrl-C stops long work cleanly: the first SIGINT sets a flag that loops check, so everything
/// computed so far is written (marked incomplete); a second SIGINT exits at once.

namespace revisit {

/// Installs the handler (idempotent) and clears the flag.
void InstallInterruptHandler();
bool InterruptRequested();

}  // namespace revisit
