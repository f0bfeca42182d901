#include "io/allocation_budget.hpp"

#include <cstdlib>
#include <cstring>
#include <new>

namespace revisit {
namespace {

struct Budget {
    std::size_t left = 0;
    bool active = false;
};
thread_local Budget t_budget;

/// Allocations below this size are not charged: a lying size field asks for one large block, while
/// small blocks (strings, MRPT's exception backtraces, built while an exception is being thrown, where
/// a second exception would terminate) are bounded by the bytes read to make them.
constexpr std::size_t kChargedFrom = 64 << 10;  // [bytes]

/// Charges `bytes` to the active budget; throws std::bad_alloc when it would be exceeded.
void Charge(std::size_t bytes) {
    Budget& b = t_budget;
    if (!b.active || bytes < kChargedFrom) return;
    if (bytes > b.left) {
        b.active = false;  // the exception's own allocation and the unwinding must not fail again
        throw std::bad_alloc();
    }
    b.left -= bytes;
}

void* AlignedAllocate(std::size_t size, std::size_t alignment) {
    Charge(size);
    if (alignment < sizeof(void*)) alignment = sizeof(void*);
    // aligned_alloc needs a size that is a multiple of the alignment.
    const std::size_t rounded = (size + alignment - 1) / alignment * alignment;
    void* p = std::aligned_alloc(alignment, rounded == 0 ? alignment : rounded);
    // MRPT writes through the pointer without checking it: fail here, where it can be reported.
    if (!p) throw std::bad_alloc();
    return p;
}

}  // namespace

AllocationBudget::AllocationBudget(std::size_t bytes) { t_budget = Budget{bytes, true}; }
AllocationBudget::~AllocationBudget() { t_budget.active = false; }

}  // namespace revisit

// MRPT's aligned allocation, defined here so that the executable's definition is the one every MRPT
// library calls (symbol interposition); mrpt::aligned_free (std::free) releases it.
namespace mrpt {
void* aligned_malloc(std::size_t size, std::size_t alignment) { return revisit::AlignedAllocate(size, alignment); }
void* aligned_calloc(std::size_t bytes, std::size_t alignment) {
    void* p = revisit::AlignedAllocate(bytes, alignment);
    std::memset(p, 0, bytes);
    return p;
}
}  // namespace mrpt

// The global operator new, bounded inside a budget scope. Replaced as a set (new, new[], their
// nothrow forms and every matching delete) on malloc/free, so that allocation and release always
// pair, also under AddressSanitizer, which still checks every block through malloc/free.
void* operator new(std::size_t size) {
    revisit::Charge(size);
    if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
    throw std::bad_alloc();
}
void* operator new[](std::size_t size) { return ::operator new(size); }
void* operator new(std::size_t size, const std::nothrow_t&) noexcept {
    try {
        return ::operator new(size);
    } catch (...) {
        return nullptr;
    }
}
void* operator new[](std::size_t size, const std::nothrow_t&) noexcept { return ::operator new(size, std::nothrow); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
void operator delete(void* p, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept { std::free(p); }
