#include "core/allocator.hpp"

#include <cstdlib>  // defines __GLIBC__ when the C library is glibc

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace revisit {

void TuneAllocator() {
#if defined(__GLIBC__)
    // Grow and trim heaps in steps of this much: repeated large temporaries then reuse touched pages.
    // (Setting M_MMAP_THRESHOLD or M_TRIM_THRESHOLD instead made the tree query slower: measured 4.5
    // and 4.0 ms.)
    mallopt(M_TOP_PAD, 64 << 20);  // [bytes]
    // Any of these settings also freezes glibc's mmap threshold at its start, 128 KiB: once the data a
    // long run keeps had used up the heap's pad, every temporary of 128 KiB or more (a scan's rays, a
    // map's grids and voxel sets) was a fresh mapping, faulted in page by page and unmapped again
    // (docs/performance.md, "Page faults on long runs"). Such temporaries now grow the heap. Arrays of
    // more than a few MiB keep their own mappings: freed, they go back at once instead of staying in
    // the heap beside the next, larger one (the global map's arrays; 32 MiB raised the peak by 20 MiB).
    mallopt(M_MMAP_THRESHOLD, 4 << 20);  // [bytes]
    // One heap for every thread. A thread's own heap (TBB workers, the read-ahead thread) is at most
    // 64 MiB, so with that pad it is never trimmed: its high-water mark stayed resident for the whole
    // run (~25 MiB of the demo's peak, issue 19). The threads allocate little: the per-scan work
    // keeps its buffers.
    mallopt(M_ARENA_MAX, 1);
#endif
}

void ReleaseFreeMemory() {
#if defined(__GLIBC__)
    malloc_trim(0);
#endif
}

}  // namespace revisit
