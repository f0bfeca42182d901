#include "core/allocator.hpp"

#include <cstdlib>  // defines __GLIBC__ when the C library is glibc

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace revisit {

void TuneAllocator() {
#if defined(__GLIBC__)
    // Grow and trim heaps in steps of this much: repeated large temporaries then reuse touched pages.
    // (Setting M_MMAP_THRESHOLD or M_TRIM_THRESHOLD instead would switch off glibc's dynamic mmap
    // threshold and make it slower: measured 4.5 and 4.0 ms.)
    mallopt(M_TOP_PAD, 64 << 20);  // [bytes]
#endif
}

}  // namespace revisit
