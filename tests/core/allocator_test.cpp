/// The command line's allocator tuning (core/allocator.hpp): a large temporary asked for when the
/// heap's pad is used up grows the heap instead of getting a fresh mapping of its own, whose pages
/// would be faulted in on every use and unmapped again.
#include <gtest/gtest.h>

#include <cstdlib>
#include <vector>

#include "core/allocator.hpp"

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace revisit {
namespace {

#if defined(__GLIBC__)
TEST(Allocator, ALargeTemporaryGrowsTheHeapWhenItsPadIsUsedUp) {
    TuneAllocator();
    // Long-lived data taking the heap's top (mallinfo2().keepcost: what is left of it), in blocks
    // below the mapping threshold glibc starts with (128 KiB), until less than the temporary is left.
    constexpr std::size_t kBlock = 64 << 10;      // [bytes]
    constexpr std::size_t kTemporary = 1 << 20;   // [bytes] e.g. a scan's rays
    std::vector<void*> kept;
    for (int i = 0; i < 8192 && mallinfo2().keepcost >= kTemporary; ++i) kept.push_back(std::malloc(kBlock));
    ASSERT_LT(mallinfo2().keepcost, kTemporary) << "the heap's top never came below the temporary's size";

    const std::size_t mapped_before = mallinfo2().hblks;
    void* temporary = std::malloc(kTemporary);
    ASSERT_NE(temporary, nullptr);
    // With the threshold frozen at 128 KiB (any heap setting freezes it) this was a mapping of its own.
    EXPECT_EQ(mallinfo2().hblks, mapped_before) << "a 1 MiB temporary was mapped instead of taken from the heap";

    std::free(temporary);
    for (void* block : kept) std::free(block);
}
#endif

}  // namespace
}  // namespace revisit
