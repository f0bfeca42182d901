#pragma once
/// Process-wide allocator tuning for the command line (glibc only; a no-op elsewhere).

namespace revisit {

/// Keeps large temporary buffers (tree matches, point clouds, images) in the heap for reuse instead of
/// mapping fresh pages for each: glibc maps blocks above a dynamic threshold and the page faults of
/// touching them again on every call cost more than the work (tree query at 10,000 stored maps: 2.6 ms
/// -> 1.3 ms, `revisit bench --only tree`). Call once, early in main.
void TuneAllocator();

/// Returns the heap's free pages to the system (what the top pad and freed blocks keep resident), so
/// that a phase that follows peaks from the live data alone. Milliseconds; between phases, not per item.
void ReleaseFreeMemory();

}  // namespace revisit
